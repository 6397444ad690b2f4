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
