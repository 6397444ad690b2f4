// The trust gate on the measured depth offset (issue 29 §3): synthetic
// estimate sequences, one a second, as the daemon feeds them.
#include <gtest/gtest.h>

#include "algo/offset_gate.hpp"

#include <vector>

using namespace depthkey;

namespace {

LatencyEstimator::Estimate good(double offsetMs)
{
	LatencyEstimator::Estimate e;
	e.valid = true;
	e.offsetMs = offsetMs;
	e.correlation = 0.8;
	e.peakMargin = 0.4;
	e.colourMotionPerS = 0.7;
	e.depthFrames = 120;
	e.maxLagMs = 300;
	return e;
}

// Feeds the estimates with pairing that never fails; the final gate.
struct Feed {
	OffsetGate gate;
	uint64_t paired = 0, unpaired = 0;
	void add(const LatencyEstimator::Estimate &e, uint64_t newPaired = 25, uint64_t newUnpaired = 0)
	{
		paired += newPaired;
		unpaired += newUnpaired;
		gate.update(e, paired, unpaired);
	}
};

} // namespace

TEST(OffsetGate, MeasuringUntilAnEstimate)
{
	Feed f;
	f.add(LatencyEstimator::Estimate{});
	EXPECT_EQ(f.gate.state(), OffsetGate::State::Measuring);
	EXPECT_FALSE(f.gate.haveApplied());
	EXPECT_EQ(f.gate.describe(), "measuring, none applied");
}

TEST(OffsetGate, AppliesTheMedianOfSteadyEstimatesOnly)
{
	Feed f;
	const double offsets[] = { -41, -39, -44, -36, -40 };
	for (size_t k = 0; k < 4; ++k) {
		f.add(good(offsets[k]));
		EXPECT_FALSE(f.gate.haveApplied()) << k;
		EXPECT_EQ(f.gate.state(), OffsetGate::State::Held);
		EXPECT_NE(f.gate.reason().find("steady estimates"), std::string::npos) << f.gate.reason();
	}
	f.add(good(offsets[4]));
	ASSERT_TRUE(f.gate.haveApplied());
	EXPECT_EQ(f.gate.appliedMs(), -40);
	EXPECT_EQ(f.gate.state(), OffsetGate::State::Applied);
	EXPECT_EQ(f.gate.describe(), "measured -40 ms, applied -40 ms");
}

// The reported run: -215 ms at 4 s, then estimates all over the place.
TEST(OffsetGate, HoldsTheReportedUnsteadySequence)
{
	Feed f;
	LatencyEstimator::Estimate first = good(-215);
	first.correlation = 0.88;
	f.add(first);
	for (double ms : { 86, 55, 39, 46, 40, 2, 83, 11, 46, 63, 1, 68, 98, -24, 2 })
		f.add(good(ms));
	EXPECT_FALSE(f.gate.haveApplied());
	EXPECT_EQ(f.gate.state(), OffsetGate::State::Held);
	EXPECT_NE(f.gate.reason().find("unsteady"), std::string::npos) << f.gate.reason();
	EXPECT_NE(f.gate.describe().find("none applied, held: unsteady"), std::string::npos) << f.gate.describe();
}

TEST(OffsetGate, EachWeakEstimateHoldsWithItsReason)
{
	struct Case {
		const char *what;
		LatencyEstimator::Estimate e;
		const char *reason;
	};
	std::vector<Case> cases;
	LatencyEstimator::Estimate e = good(275); // the blocked start's +275 ms
	cases.push_back({ "edge", e, "edge of the +-300 ms search" });
	e = good(-258);
	cases.push_back({ "edge, negative", e, "edge of the +-300 ms search" });
	e = good(-40);
	e.peakMargin = 0.05;
	cases.push_back({ "unclear peak", e, "peak unclear" });
	e = good(-40);
	e.correlation = 0.45;
	cases.push_back({ "low correlation", e, "correlation 0.45" });
	e = LatencyEstimator::Estimate{}; // a still room: no valid estimate at all
	e.depthFrames = 120;
	e.maxLagMs = 300;
	e.offsetMs = -300;
	cases.push_back({ "invalid", e, "too little motion" });
	e = good(-40);
	e.colourMotionPerS = 0.01;
	cases.push_back({ "still", e, "too little motion" });
	e = good(-40);
	e.depthFrames = 40;
	cases.push_back({ "few frames", e, "40 depth frames" });
	for (const Case &c : cases) {
		Feed f;
		for (int k = 0; k < 20; ++k)
			f.add(c.e);
		EXPECT_FALSE(f.gate.haveApplied()) << c.what;
		EXPECT_NE(f.gate.reason().find(c.reason), std::string::npos) << c.what << ": " << f.gate.reason();
		EXPECT_EQ(f.gate.describe().find("measured -300"), std::string::npos) << f.gate.describe();
	}
}

// A weak estimate breaks the run of steady ones: stability counts
// consecutive estimates.
TEST(OffsetGate, AWeakEstimateRestartsTheCount)
{
	Feed f;
	for (int k = 0; k < 4; ++k)
		f.add(good(-40));
	LatencyEstimator::Estimate weak = good(-40);
	weak.peakMargin = 0.01;
	f.add(weak);
	for (int k = 0; k < 4; ++k)
		f.add(good(-40));
	EXPECT_FALSE(f.gate.haveApplied());
	f.add(good(-40));
	EXPECT_TRUE(f.gate.haveApplied());
}

TEST(OffsetGate, FollowsASteadyMoveButNotJitter)
{
	Feed f;
	for (int k = 0; k < 5; ++k)
		f.add(good(-40));
	for (double ms : { -41.0, -42.0, -41.0, -39.0, -42.0 })
		f.add(good(ms));
	EXPECT_EQ(f.gate.appliedMs(), -40); // within kApplyStepMs: no change
	for (int k = 0; k < 5; ++k)
		f.add(good(-60));
	EXPECT_EQ(f.gate.appliedMs(), -60);
}

TEST(OffsetGate, TakesBackAnOffsetThatMakesPairingWorse)
{
	Feed f;
	for (int k = 0; k < 5; ++k)
		f.add(good(-40));
	ASSERT_EQ(f.gate.appliedMs(), -40);
	for (int k = 0; k < 5; ++k)
		f.add(good(-90)); // a wrong but steady measurement
	ASSERT_EQ(f.gate.appliedMs(), -90);
	// Pairing fails for a fifth of the colour frames from then on.
	for (size_t k = 0; k < OffsetGate::kJudgeUpdates; ++k)
		f.add(good(-90), 20, 5);
	EXPECT_TRUE(f.gate.haveApplied());
	EXPECT_EQ(f.gate.appliedMs(), -40);
	EXPECT_EQ(f.gate.state(), OffsetGate::State::Held);
	// The same measurement is not applied again.
	for (int k = 0; k < 10; ++k)
		f.add(good(-90));
	EXPECT_EQ(f.gate.appliedMs(), -40);
	EXPECT_NE(f.gate.reason().find("taken back"), std::string::npos) << f.gate.reason();
	// A measurement elsewhere is.
	for (int k = 0; k < 5; ++k)
		f.add(good(-45));
	EXPECT_EQ(f.gate.appliedMs(), -45);
}

TEST(OffsetGate, TheFirstOffsetTakenBackLeavesNoneApplied)
{
	Feed f;
	for (int k = 0; k < 5; ++k)
		f.add(good(250), 25, 0);
	ASSERT_TRUE(f.gate.haveApplied());
	for (size_t k = 0; k < OffsetGate::kJudgeUpdates; ++k)
		f.add(good(250), 10, 15);
	EXPECT_FALSE(f.gate.haveApplied());
	EXPECT_EQ(f.gate.appliedMs(), 0);
}

TEST(OffsetGate, KeepsAnOffsetWhenPairingStaysAsItWas)
{
	Feed f;
	for (int k = 0; k < 5; ++k)
		f.add(good(-40), 24, 1); // 4 % unpaired before
	for (size_t k = 0; k < OffsetGate::kJudgeUpdates + 3; ++k)
		f.add(good(-40), 24, 1);
	EXPECT_EQ(f.gate.appliedMs(), -40);
	EXPECT_EQ(f.gate.state(), OffsetGate::State::Applied);
}

TEST(OffsetGate, UnpairedShare)
{
	EXPECT_EQ(unpairedShare(10, 0, 10, 0), 0.0);
	EXPECT_DOUBLE_EQ(unpairedShare(10, 2, 40, 12), 10.0 / 40.0);
}
