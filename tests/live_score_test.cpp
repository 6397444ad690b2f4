// The daemon's live score (algo/live_score.hpp, issue 29): the figures of
// depthkey-eval's scorer, averaged per frame over the last 5 s of capture
// time and since the start.
#include "algo/live_score.hpp"
#include "allocation_counter.hpp"
#include "mask_rect.hpp"

#include <gtest/gtest.h>

using namespace depthkey;
using depthkey::test::maskRect;

namespace {

constexpr uint64_t kSecond = 1'000'000'000ull;

} // namespace

TEST(LiveScore, NothingScoredWithoutTruth)
{
	LiveScore live;
	live.add(maskRect(20, 20, 2, 2, 8, 8), Gray8Image{}, kSecond);
	live.addWithoutLecturer(Gray8Image{}, kSecond);
	EXPECT_FALSE(live.scoring());
	EXPECT_EQ(live.sinceStart().frames, 0u);
	EXPECT_EQ(live.recent().frames, 0u);
}

TEST(LiveScore, AgreesWithTheOfflineScorerFrameByFrame)
{
	LiveScore live;
	SegmentationScorer offline(2);
	ScoreAverage average;
	const Gray8Image truth = maskRect(40, 30, 10, 5, 25, 25);
	for (int shift = 0; shift < 6; ++shift) {
		Gray8Image predicted = maskRect(40, 30, 10 + shift, 5, 25 + shift, 25);
		live.add(predicted, truth, uint64_t(shift + 1) * kSecond / 25);
		average.add(offline.score(predicted, truth));
	}
	EXPECT_EQ(live.sinceStart().frames, 6u);
	EXPECT_DOUBLE_EQ(live.sinceStart().iou, average.mean().iou);
	EXPECT_DOUBLE_EQ(live.sinceStart().boundaryF, average.mean().boundaryF);
	EXPECT_DOUBLE_EQ(live.recent().iou, average.mean().iou); // all within 5 s
	EXPECT_LT(live.sinceStart().iou, 1.0);
}

TEST(LiveScore, BoardOnlyFrameScoresAsAnEmptyLayer)
{
	LiveScore live;
	const Gray8Image truth = maskRect(20, 20, 4, 4, 12, 12);
	live.addWithoutLecturer(truth, kSecond);
	EXPECT_DOUBLE_EQ(live.sinceStart().iou, 0.0);
	EXPECT_DOUBLE_EQ(live.sinceStart().boundaryF, 0.0);
	// An empty room shown as an empty layer is right.
	live.reset();
	live.addWithoutLecturer(Gray8Image(20, 20, 0), kSecond);
	EXPECT_DOUBLE_EQ(live.sinceStart().iou, 1.0);
}

TEST(LiveScore, RecentCoversTheLastFiveSecondsOfCaptureTime)
{
	LiveScore live;
	const Gray8Image truth = maskRect(20, 20, 4, 4, 12, 12);
	// 10 s of bad frames, then 5 s of perfect ones at 10 fps.
	uint64_t t = 0;
	for (int i = 0; i < 100; ++i, t += kSecond / 10)
		live.addWithoutLecturer(truth, t);
	for (int i = 0; i < 50; ++i, t += kSecond / 10)
		live.add(truth, truth, t);
	EXPECT_EQ(live.recent().frames, 50u);
	EXPECT_DOUBLE_EQ(live.recent().iou, 1.0);
	EXPECT_DOUBLE_EQ(live.recent().boundaryF, 1.0);
	EXPECT_EQ(live.sinceStart().frames, 150u);
	EXPECT_NEAR(live.sinceStart().iou, 50.0 / 150.0, 1e-12);
}

TEST(LiveScore, RepeatedFrameStandingForAnOlderTimeStaysInItsWindow)
{
	LiveScore live;
	const Gray8Image truth = maskRect(20, 20, 4, 4, 12, 12);
	live.add(truth, truth, 10 * kSecond);
	live.addWithoutLecturer(truth, 4 * kSecond); // stands for a time 6 s before the newest
	EXPECT_EQ(live.recent().frames, 1u);
	EXPECT_EQ(live.sinceStart().frames, 2u);
}

TEST(LiveScore, NoAllocationPerFrameOnceSized)
{
	LiveScore live;
	const Gray8Image truth = maskRect(64, 48, 10, 10, 30, 40);
	const Gray8Image predicted = maskRect(64, 48, 11, 10, 31, 40);
	live.add(predicted, truth, kSecond);
	live.addWithoutLecturer(truth, 2 * kSecond);
	if (!test::allocationCounting())
		GTEST_SKIP() << "a sanitizer build: operator new is not counted";
	test::CountAllocations counter;
	for (int i = 0; i < 2000; ++i) { // more than the ring holds
		live.add(predicted, truth, uint64_t(i + 3) * kSecond / 25);
		live.addWithoutLecturer(truth, uint64_t(i + 3) * kSecond / 25);
	}
	EXPECT_EQ(counter.count(), 0u);
}

// A shed frame: the last layer that went out stays on screen, scored
// against the lost frame's truth.
TEST(LiveScore, ShedFrameScoresTheLastLayerAgainstItsOwnTruth)
{
	LiveScore live;
	const Gray8Image here = maskRect(40, 30, 5, 5, 15, 25);
	const Gray8Image movedOn = maskRect(40, 30, 10, 5, 20, 25); // the lecturer moved 5 px
	live.addRepeated(movedOn, kSecond); // nothing went out yet: nothing to repeat
	EXPECT_EQ(live.sinceStart().frames, 0u);
	live.add(here, here, kSecond);
	live.addRepeated(movedOn, kSecond + kSecond / 25);
	SegmentationScorer offline(2);
	const SegmentationScore stale = offline.score(here, movedOn);
	EXPECT_EQ(live.sinceStart().frames, 2u);
	EXPECT_DOUBLE_EQ(live.sinceStart().iou, (1.0 + stale.iou) / 2);
	EXPECT_LT(stale.iou, 1.0);
	// After a board-only frame the board alone stays on screen.
	live.reset();
	live.add(here, here, kSecond);
	live.addWithoutLecturer(here, 2 * kSecond);
	live.addRepeated(here, 3 * kSecond);
	EXPECT_DOUBLE_EQ(live.sinceStart().iou, 1.0 / 3);
}
