// The constant-rate stream's arithmetic (issue 29 point 5): how many colour
// frame slots went without a published frame between two keyed frames.
#include "algo/capture_slots.hpp"

#include <gtest/gtest.h>

using namespace depthkey;

namespace {
constexpr uint64_t kMs = 1'000'000, kInterval = 40 * kMs, kSecond = 1000 * kMs;
} // namespace

TEST(CaptureSlots, CountsTheSlotsBetweenTwoCapturesRoundingJitter)
{
	EXPECT_EQ(skippedCaptureSlots(1000 * kMs, 1040 * kMs, kInterval, kSecond), 0u); // the next slot
	EXPECT_EQ(skippedCaptureSlots(1000 * kMs, 1058 * kMs, kInterval, kSecond), 0u); // late, not a slot
	EXPECT_EQ(skippedCaptureSlots(1000 * kMs, 1062 * kMs, kInterval, kSecond), 1u); // one shed
	EXPECT_EQ(skippedCaptureSlots(1000 * kMs, 1118 * kMs, kInterval, kSecond), 2u); // two, early
	EXPECT_EQ(skippedCaptureSlots(1000 * kMs, 2000 * kMs, kInterval, kSecond), 24u); // a second: filled
}

TEST(CaptureSlots, NothingAtTheStartBackwardsOrAfterAnOutage)
{
	EXPECT_EQ(skippedCaptureSlots(0, 1200 * kMs, kInterval, kSecond), 0u);          // no frame yet
	EXPECT_EQ(skippedCaptureSlots(1200 * kMs, 1000 * kMs, kInterval, kSecond), 0u); // a restart
	EXPECT_EQ(skippedCaptureSlots(1000 * kMs, 2001 * kMs, kInterval, kSecond), 0u); // an outage
	EXPECT_EQ(skippedCaptureSlots(1000 * kMs, 1200 * kMs, 0, kSecond), 0u);
}

// Slots count from the previous slot, not the previous jittered capture:
// the frames out between two captures number the slots between them.
TEST(CaptureSlots, TheClockKeepsCountUnderJitterAndFollowsDrift)
{
	CaptureSlotClock clock;
	clock.configure(20 * kMs, kSecond);
	EXPECT_EQ(clock.skippedBefore(1000 * kMs), 0u); // the first frame
	// Every other frame shed, the kept ones 9 ms late or 9 ms early in turn:
	// per-gap rounding would fill 2 then 0 slots (49 ms, then 31 ms gaps).
	uint64_t out = 1, t = 1000;
	for (int i = 1; i <= 50; i++) {
		t += 40;
		const uint64_t capture = (t + (i % 2 ? 9 : -9)) * kMs;
		const uint64_t skipped = clock.skippedBefore(capture);
		if (skipped) {
			EXPECT_EQ(clock.slotNs(1), (t - 20) * kMs) << "frame " << i;
		}
		out += skipped + 1;
	}
	EXPECT_EQ(out, 101u); // 2000 ms of 20 ms slots, both ends counted
	// A camera 5% fast: the slots follow its time, no frame is counted twice.
	uint64_t fast = t * kMs;
	for (int i = 0; i < 100; i++) {
		fast += 19 * kMs;
		EXPECT_EQ(clock.skippedBefore(fast), 0u) << "frame " << i;
	}
	clock.reset();
	EXPECT_EQ(clock.skippedBefore(fast + 100 * kMs), 0u); // starts again
}
