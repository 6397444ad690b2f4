#include "hal/event_loop.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

using namespace depthkey;

TEST(EventLoop, PeriodicTimerFiresAndCanCancelItselfInsideItsCallback)
{
	EventLoop loop;
	ASSERT_EQ(loop.open(), 0);
	EventSource periodic, stopper;
	int ticks = 0;
	ASSERT_EQ(loop.addPeriodic(2000, [&] {
		if (++ticks == 5)
			periodic.reset(); // destroying the running source must be safe
	}, periodic), 0);
	ASSERT_EQ(loop.addTimer(100000, [&] { loop.exit(0); }, stopper), 0);
	EXPECT_EQ(loop.run(), 0);
	EXPECT_EQ(ticks, 5);
}

TEST(EventLoop, IoSourceReportsReadiness)
{
	EventLoop loop;
	ASSERT_EQ(loop.open(), 0);
	int fds[2];
	ASSERT_EQ(pipe(fds), 0);
	EventSource io, writer;
	char got = 0;
	ASSERT_EQ(loop.addIo(fds[0], 0x001 /* EPOLLIN */, [&](uint32_t) {
		ASSERT_EQ(read(fds[0], &got, 1), 1);
		loop.exit(3);
	}, io), 0);
	ASSERT_EQ(loop.addTimer(1000, [&] { ASSERT_EQ(write(fds[1], "x", 1), 1); }, writer), 0);
	EXPECT_EQ(loop.run(), 3);
	EXPECT_EQ(got, 'x');
	close(fds[0]);
	close(fds[1]);
}

TEST(EventLoop, ResetSourceIsNeverCalledBack)
{
	EventLoop loop;
	ASSERT_EQ(loop.open(), 0);
	EventSource timer, stopper;
	bool called = false;
	ASSERT_EQ(loop.addTimer(1000, [&] { called = true; }, timer), 0);
	timer.reset();
	ASSERT_EQ(loop.addTimer(20000, [&] { loop.exit(0); }, stopper), 0);
	loop.run();
	EXPECT_FALSE(called);
}
