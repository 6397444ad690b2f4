#include "hal/sim/lecture_simulator.hpp"
#include "hal/sim/sim_timing.hpp"
#include "tests/sim_test_util.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <vector>

using namespace depthkey;

namespace {

// Colour time minus the true capture time of the depth frame the daemon
// pairs with it, for the colour frames that have one.
std::vector<double> pairingOffsets(const sim::SimTiming &timing, int frames)
{
	std::vector<double> offsets;
	for (int n = 0; n < frames; ++n) {
		double t = timing.colourTime(n);
		int64_t m = timing.latestDepthAt(t);
		if (m < 0)
			continue;
		EXPECT_LE(timing.depthStamp(m), t);
		EXPECT_GT(timing.depthStamp(m + 1), t); // the newest one
		offsets.push_back(t - timing.depthCapture(m));
	}
	return offsets;
}

} // namespace

TEST(SimTiming, DepthIsOlderThanColourByLatencyPlusUpToAPeriod)
{
	SimSettings s; // latency 40 ms, depth jitter 5 ms, 10 fps
	sim::SimTiming timing;
	timing.configure(s, 25, 10);
	std::vector<double> offsets = pairingOffsets(timing, 300);
	ASSERT_GT(offsets.size(), 290u);
	double sum = 0;
	for (double o : offsets) {
		EXPECT_GE(o, 0.040 - 0.010);
		EXPECT_LE(o, 0.040 + 0.100 + 0.010);
		sum += o;
	}
	double mean = sum / offsets.size();
	std::printf("colour - depth capture time: mean %.1f ms\n", mean * 1000);
	EXPECT_NEAR(mean, 0.040 + 0.050, 0.010);
}

TEST(SimTiming, JitterHasItsSpreadAndSwitchesOff)
{
	SimSettings s;
	s.colourJitterMs = 2.0;
	sim::SimTiming timing;
	timing.configure(s, 25, 10);
	double sum2 = 0;
	const int n = 2000;
	for (int i = 0; i < n; ++i) {
		double d = timing.colourTime(i + 1) - timing.colourTime(i) - 0.04;
		sum2 += d * d;
	}
	// Difference of two uniforms in +-j: sigma = j * sqrt(2/3).
	EXPECT_NEAR(std::sqrt(sum2 / n), 0.002 * std::sqrt(2.0 / 3.0), 0.0002);

	s = test::cleanSim();
	timing.configure(s, 25, 10);
	for (int i = 0; i < 50; ++i)
		EXPECT_NEAR(timing.colourTime(i + 1) - timing.colourTime(i), 0.04, 1e-12);
	for (double o : pairingOffsets(timing, 100)) {
		EXPECT_GE(o, 0.0);
		EXPECT_LE(o, 0.100 + 1e-9);
	}
}

// The paper sees the lecturer's fast hands 10-50 px apart in colour and
// depth: the simulated timing must produce that on the moving hand.
TEST(SimTiming, FastHandShowsTheOffsetInPixels)
{
	SimSettings s;
	LectureSimulator sim;
	sim.configure(s, 640, 480);
	sim::SimTiming timing;
	timing.configure(s, 25, 10);
	std::vector<sim::Capsule> atColour, atDepth;
	std::vector<double> shifts;
	for (int n = 0; n < 300; ++n) {
		double t = timing.colourTime(n);
		int64_t m = timing.latestDepthAt(t);
		if (m < 0)
			continue;
		sim.poseLecturer(t, atColour);
		sim.poseLecturer(timing.depthCapture(m), atDepth);
		double x0, y0, x1, y1;
		const auto &hand0 = atColour[12].a, &hand1 = atDepth[12].a; // right hand
		sim.rig().colour().project(hand0.cast<double>(), x0, y0);
		sim.rig().colour().project(hand1.cast<double>(), x1, y1);
		shifts.push_back(std::hypot(x1 - x0, y1 - y0));
	}
	std::sort(shifts.begin(), shifts.end());
	double p90 = shifts[shifts.size() * 9 / 10], top = shifts.back();
	std::printf("right hand shift between paired frames: 90th percentile %.1f px, max %.1f px\n", p90, top);
	// Most of the time tens of pixels; raising the hand to the board (about
	// 2 m/s at its fastest) reaches about 100.
	EXPECT_GE(p90, 10.0);
	EXPECT_LE(p90, 60.0);
	EXPECT_LE(top, 130.0);
}
