// Reconnect timing against a fake clock: the retry schedule while a device is
// away, how quickly it is found on return, and stall detection.
#include <gtest/gtest.h>

#include "hal/reconnect_backoff.hpp"

#include <vector>

using namespace depthkey;

TEST(ReconnectBackoff, DoublesFrom100msToACapOf250ms)
{
	ReconnectBackoff b;
	std::vector<uint64_t> delays;
	for (int i = 0; i < 7; i++)
		delays.push_back(b.nextDelayUs() / 1000);
	EXPECT_EQ(delays, (std::vector<uint64_t>{ 100, 200, 250, 250, 250, 250, 250 }));
	EXPECT_EQ(b.attempts(), 7u);
	b.reset();
	EXPECT_EQ(b.nextDelayUs(), 100'000u);
}

// A device away for a while comes back; with a fake clock, find when the
// first retry after its return happens: never more than the cap later.
TEST(ReconnectBackoff, ReturningDeviceIsRetriedWithinTheCap)
{
	for (uint64_t returnsAtMs : { 50, 150, 700, 1600, 5000, 60000 }) {
		ReconnectBackoff b;
		uint64_t nowMs = 0;
		while (nowMs < returnsAtMs)
			nowMs += b.nextDelayUs() / 1000; // each retry fails until then
		EXPECT_LE(nowMs - returnsAtMs, ReconnectBackoff::kMaxUs / 1000) << returnsAtMs;
		EXPECT_LT(nowMs - returnsAtMs, 2000u) << "issue 5: recovery within 2 s";
	}
}

TEST(ReconnectBackoff, ADeviceFailingRightAfterOpenKeepsBackingOff)
{
	// Opened, then lost before any good frame: no reset, so no 100 ms spin.
	ReconnectBackoff b;
	b.nextDelayUs();
	b.nextDelayUs();
	EXPECT_EQ(b.nextDelayUs(), ReconnectBackoff::kMaxUs);
}

TEST(StallDetector, StallsOnlyAfterTheTimeoutWithoutFrames)
{
	StallDetector s(1'000'000);
	uint64_t now = 5'000'000;
	s.arm(now);
	EXPECT_FALSE(s.stalled(now + 1'000'000));
	EXPECT_TRUE(s.stalled(now + 1'000'001));
	s.frame(now + 900'000);
	EXPECT_FALSE(s.stalled(now + 1'500'000));
	EXPECT_TRUE(s.stalled(now + 2'000'000));
	EXPECT_FALSE(s.stalled(now)); // a clock read before the frame is not a stall
}
