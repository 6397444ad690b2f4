// BackgroundJob: the work runs on another thread, its completion on the
// loop's; one job at a time.
#include "hal/background_job.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

using namespace depthkey;

TEST(BackgroundJob, WorkOffTheLoopDoneOnIt)
{
	EventLoop loop;
	ASSERT_EQ(loop.open(), 0);
	BackgroundJob job;
	std::thread::id workThread, doneThread;
	int result = 0, ticks = 0;
	EventSource tick;
	// The loop keeps running (ticking) while the work takes its time.
	loop.addPeriodic(5000, [&] { ticks++; }, tick);
	ASSERT_EQ(job.start(
			  loop,
			  [&] {
				  workThread = std::this_thread::get_id();
				  std::this_thread::sleep_for(std::chrono::milliseconds(100));
				  result = 42;
			  },
			  [&] {
				  doneThread = std::this_thread::get_id();
				  EXPECT_EQ(result, 42);
				  EXPECT_FALSE(job.running());
				  // The next job may start from done(): eventfd and source are reused.
				  EXPECT_EQ(job.start(loop, [&] { result = 7; }, [&] { loop.exit(0); }), 0);
			  }),
		  0);
	EXPECT_TRUE(job.running());
	EXPECT_EQ(job.start(loop, [] {}, [] {}), -EBUSY);
	EXPECT_EQ(loop.run(), 0);
	EXPECT_FALSE(job.running());
	EXPECT_NE(workThread, std::this_thread::get_id());
	EXPECT_EQ(doneThread, std::this_thread::get_id());
	EXPECT_GE(ticks, 10);
	EXPECT_EQ(result, 7);
}
