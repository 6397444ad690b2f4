// The depth latency measured from the two streams: on the simulated lecture
// (all artefacts on) the simulator's latency is found within 10 ms, for the
// default 40 ms and for another; with no motion there is no estimate.
#include <gtest/gtest.h>

#include "algo/latency_estimator.hpp"
#include "hal/sim/sim_sequence.hpp"

#include <cmath>
#include <cstdio>

using namespace depthkey;

namespace {

LatencyEstimator::Estimate estimateOnSim(double latencyMs, uint64_t seed, int seconds)
{
	SimSettings sim;
	sim.seed = seed;
	sim.depthLatencyMs = latencyMs;
	SimSequence sequence;
	sequence.configure(sim, 320, 240, 25, 10);
	LatencyEstimator estimator;
	SegmentationSettings segmentation;
	estimator.configure(segmentation.nearMm, segmentation.farMm);
	ColourFrame colour;
	GroundTruth truth;
	for (int n = 0; n < 25 * seconds; ++n) {
		sequence.frame(uint64_t(n), colour, truth,
			       [&](const DepthFrame &d) { estimator.addDepth(d, d.timestampNs); });
		estimator.addColour(colour.rgb, colour.timestampNs);
	}
	return estimator.estimate();
}

// 16 s of a still room: the same colour and depth picture each frame.
LatencyEstimator::Estimate stillEstimate()
{
	LatencyEstimator estimator;
	estimator.configure(500, 1850);
	RgbImage still(64, 48, Rgb8{ 30, 60, 40 });
	DepthFrame depth;
	depth.depthMm = Gray16Image(16, 12, 2000);
	for (int n = 0; n < 400; ++n) {
		estimator.addColour(still, uint64_t(n) * 40'000'000);
		if (n % 4 == 0)
			estimator.addDepth(depth, uint64_t(n) * 40'000'000 + 40'000'000);
	}
	return estimator.estimate();
}

} // namespace

TEST(LatencyEstimator, FindsTheSimulatedDepthLatencyWithin10Ms)
{
	const std::pair<double, uint64_t> runs[] = { { 40.0, 1 }, { 40.0, 2 }, { 40.0, 3 }, { 90.0, 1 } };
	for (auto [latencyMs, seed] : runs) {
		const LatencyEstimator::Estimate e = estimateOnSim(latencyMs, seed, 12);
		std::printf("latency %.0f ms, seed %llu: offset %+.1f ms (correlation %.2f, %zu depth frames)\n",
			    latencyMs, static_cast<unsigned long long>(seed), e.offsetMs, e.correlation, e.depthFrames);
		ASSERT_TRUE(e.valid);
		EXPECT_NEAR(e.offsetMs, -latencyMs, 10.0);
	}
}

TEST(LatencyEstimator, NoMotionNoEstimate)
{
	EXPECT_FALSE(stillEstimate().valid);
}

// What the trust gate (algo/offset_gate.hpp) reads besides the offset: on
// the lecture the peak clearly beats the rest and there is motion; on a
// still scene there is none.
TEST(LatencyEstimator, ReportsPeakMarginAndMotion)
{
	const LatencyEstimator::Estimate e = estimateOnSim(40.0, 1, 12);
	EXPECT_GT(e.peakMargin, 0.15);
	EXPECT_GT(e.colourMotionPerS, 0.1);
	EXPECT_EQ(e.maxLagMs, 300);

	EXPECT_EQ(stillEstimate().colourMotionPerS, 0.0);
}
