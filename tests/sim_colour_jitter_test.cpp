// Issue 31 point 10: sim.colour_jitter_ms reaches the live simulated colour
// camera's frames. Its capture instants jitter uniformly by +- the setting
// around the period, so the interval between two timestamps has a standard
// deviation of sqrt(2/3) times the setting (two independent uniforms); each
// frame shows the scene at its timestamp. The jitter is the seed's hash
// noise (deterministic); only the event loop's own scheduling noise (about
// a millisecond on a loaded machine) is not.
#include "hal/event_loop.hpp"
#include "hal/sim/lecture_simulator.hpp"
#include "hal/sim/sim_cameras.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

using namespace depthkey;

namespace {

constexpr int kFrames = 80;

struct Captured {
	std::vector<uint64_t> stampsNs;
	ColourFrame last;
};

Captured capture(double jitterMs)
{
	Captured out;
	EventLoop loop;
	EXPECT_EQ(loop.open(), 0);
	ColourCameraSettings colour;
	colour.width = 64;
	colour.height = 48;
	colour.fps = 50; // the jitter is kept below 0.45 of the 20 ms period
	SimSettings sim;
	sim.colourJitterMs = jitterMs;
	SimColourCamera camera(colour, sim);
	EXPECT_EQ(camera.start(
			  loop,
			  [&](const ColourFrame &f) {
				  out.stampsNs.push_back(f.timestampNs);
				  if (out.stampsNs.size() == kFrames) {
					  out.last = f;
					  loop.exit(0);
				  }
			  },
			  [](const DeviceStatus &) {}),
		  0);
	EventSource timeout;
	EXPECT_EQ(loop.addTimer(20'000'000, [&] { loop.exit(1); }, timeout), 0);
	EXPECT_EQ(loop.run(), 0);
	camera.stop();
	return out;
}

double intervalSdMs(const std::vector<uint64_t> &stampsNs)
{
	std::vector<double> intervals;
	for (size_t i = 1; i < stampsNs.size(); i++)
		intervals.push_back((double(stampsNs[i]) - double(stampsNs[i - 1])) / 1e6);
	double mean = 0, var = 0;
	for (double d : intervals)
		mean += d / intervals.size();
	for (double d : intervals)
		var += (d - mean) * (d - mean) / (intervals.size() - 1);
	return std::sqrt(var);
}

} // namespace

TEST(SimColourCamera, CaptureTimestampsJitterAsConfigured)
{
	const double jitterMs = 8.0;
	const double expectedSd = jitterMs * std::sqrt(2.0 / 3.0); // 6.5 ms
	Captured jittered = capture(jitterMs);
	Captured steady = capture(0.0);
	ASSERT_EQ(jittered.stampsNs.size(), size_t(kFrames));
	ASSERT_EQ(steady.stampsNs.size(), size_t(kFrames));
	double sd = intervalSdMs(jittered.stampsNs), sd0 = intervalSdMs(steady.stampsNs);
	std::printf("interval sd: %.2f ms at colour_jitter_ms %.1f (expected %.2f), %.2f ms at 0\n", sd, jitterMs,
		    expectedSd, sd0);
	for (size_t i = 1; i < jittered.stampsNs.size(); i++)
		EXPECT_GT(jittered.stampsNs[i], jittered.stampsNs[i - 1]) << "frame " << i << " out of order";
	// The stamps also carry the scheduler's own jitter (sd0, the steady
	// run's). On a loaded machine (a SAN build beside other builds, qemu-user)
	// it reached 4.7-14.6 ms, as much as the configured jitter: then nothing
	// can be told apart, and the test says so instead of guessing.
	if (sd0 >= expectedSd)
		GTEST_SKIP() << "the machine's own jitter (" << sd0 << " ms) is as large as the configured one";
	// Independent jitters add in quadrature: what the configured jitter adds.
	const double added = std::sqrt(std::max(0.0, sd * sd - sd0 * sd0));
	EXPECT_GT(added, 0.7 * expectedSd);
	EXPECT_LT(added, 1.3 * expectedSd);
}

TEST(SimColourCamera, FrameShowsTheSceneAtItsJitteredTimestamp)
{
	Captured jittered = capture(8.0);
	ASSERT_FALSE(jittered.last.rgb.empty());
	LectureSimulator scene;
	SimSettings sim;
	sim.colourJitterMs = 8.0;
	scene.configure(sim, 64, 48);
	ColourFrame expected;
	scene.renderColour(double(jittered.last.timestampNs / 1000u) / 1e6, expected);
	ASSERT_EQ(expected.rgb.size(), jittered.last.rgb.size());
	EXPECT_EQ(std::memcmp(expected.rgb.data(), jittered.last.rgb.data(), expected.rgb.size() * sizeof(Rgb8)), 0);
}
