// The keying worker (daemon/keying_worker.hpp) under concurrency: a full
// queue drops its oldest waiting frame and counts it, results come back in
// order, what keying reads changes only between frames, and stop() joins a
// worker in the middle of a frame. Run it under ThreadSanitizer too:
//   make SAN=thread check CHECK_ARGS=--gtest_filter='KeyingWorker*'
#include "daemon/keying_worker.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>
#include <vector>

using namespace depthkey;
using namespace std::chrono_literals;

namespace {

// Holds the worker inside a frame until opened; says when it got there.
class Gate
{
public:
	void pass()
	{
		std::unique_lock lock(mutex_);
		entered_++;
		changed_.notify_all();
		changed_.wait(lock, [this] { return open_; });
	}
	void open()
	{
		std::lock_guard lock(mutex_);
		open_ = true;
		changed_.notify_all();
	}
	// Waits (up to a few seconds) until n frames reached the gate.
	bool waitEntered(int n)
	{
		std::unique_lock lock(mutex_);
		return changed_.wait_for(lock, 5s, [&] { return entered_ >= n; });
	}

private:
	std::mutex mutex_;
	std::condition_variable changed_;
	int entered_ = 0;
	bool open_ = false;
};

// Turns the loop until pred holds (true) or timeout passes (false). Once
// per loop: an sd-event loop that exited does not run again.
template<typename Pred>
bool runUntil(EventLoop &loop, Pred pred, std::chrono::milliseconds timeout = 5s)
{
	EventSource poll, deadline;
	loop.addPeriodic(1000, [&] {
		if (pred())
			loop.exit(0);
	}, poll);
	loop.addTimer(uint64_t(timeout.count()) * 1000, [&] { loop.exit(1); }, deadline);
	return loop.run() == 0;
}

// Submits a frame numbered sequence (its colour frame's sequence).
void submitFrame(KeyingWorker &worker, uint64_t sequence, bool mayDrop = true)
{
	KeyingJob *job = worker.nextJob(mayDrop);
	ASSERT_NE(job, nullptr);
	job->colour.sequence = sequence;
	worker.submit(job);
}

} // namespace

TEST(KeyingWorker, AFullQueueDropsTheOldestWaitingFrameAndCountsIt)
{
	for (size_t capacity : { size_t(1), size_t(2) }) {
		SCOPED_TRACE(capacity);
		EventLoop loop;
		ASSERT_EQ(loop.open(), 0);
		KeyingWorker worker;
		Gate gate;
		std::vector<uint64_t> results; // the loop's only
		ASSERT_EQ(worker.start(
				  loop, capacity, [&](KeyingJob &) { gate.pass(); },
				  [&](KeyingJob &job) { results.push_back(job.colour.sequence); }),
			  0);
		submitFrame(worker, 1);
		ASSERT_TRUE(gate.waitEntered(1)); // frame 1 is being keyed
		// capacity frames wait; each one more drops the oldest waiting.
		uint64_t sequence = 2;
		for (size_t i = 0; i < capacity; ++i)
			submitFrame(worker, sequence++);
		EXPECT_TRUE(worker.full());
		EXPECT_EQ(worker.dropped(), 0u);
		submitFrame(worker, sequence++);
		submitFrame(worker, sequence++);
		EXPECT_EQ(worker.dropped(), 2u);
		gate.open();
		ASSERT_TRUE(runUntil(loop, [&] { return worker.idle(); }));
		// Frame 1, then the newest `capacity` frames, in order.
		std::vector<uint64_t> expected{ 1 };
		for (uint64_t s = sequence - capacity; s < sequence; ++s)
			expected.push_back(s);
		EXPECT_EQ(results, expected);
		worker.stop();
	}
}

TEST(KeyingWorker, ResultsComeBackInOrderAndNoneIsLostWhenTheSourceWaits)
{
	EventLoop loop;
	ASSERT_EQ(loop.open(), 0);
	KeyingWorker worker;
	std::vector<uint64_t> results;
	std::vector<uint64_t> keyedOnWorker; // the worker's, read after stop()
	ASSERT_EQ(worker.start(
			  loop, 2,
			  [&](KeyingJob &job) {
				  keyedOnWorker.push_back(job.colour.sequence);
				  std::this_thread::sleep_for(std::chrono::microseconds(200 * (job.colour.sequence % 3)));
			  },
			  [&](KeyingJob &job) { results.push_back(job.colour.sequence); }),
		  0);
	constexpr uint64_t kFrames = 200;
	// Without dropping, the loop waits for room, taking results meanwhile.
	for (uint64_t s = 1; s <= kFrames; ++s)
		submitFrame(worker, s, false);
	ASSERT_TRUE(runUntil(loop, [&] { return worker.idle(); }));
	worker.stop();
	EXPECT_EQ(worker.dropped(), 0u);
	ASSERT_EQ(results.size(), kFrames);
	for (uint64_t s = 1; s <= kFrames; ++s)
		EXPECT_EQ(results[s - 1], s);
	EXPECT_EQ(keyedOnWorker, results);
}

// What keying reads (the pipeline, in the daemon) is the loop's to change
// when the worker is idle or from the result callback: a reload that comes
// while a frame is being keyed waits for it, and the next frame sees it.
// ThreadSanitizer checks the plain int is never read and written at once.
TEST(KeyingWorker, ASettingChangesOnlyBetweenFrames)
{
	EventLoop loop;
	ASSERT_EQ(loop.open(), 0);
	KeyingWorker worker;
	int setting = 1;      // the "pipeline": read on the worker, written by the loop
	int pending = 0;      // a reload waiting for the frame being keyed
	Gate gate;
	std::vector<std::pair<uint64_t, int>> seen; // the loop's: frame, setting it was keyed with
	ASSERT_EQ(worker.start(
			  loop, 1,
			  [&](KeyingJob &job) {
				  const int before = setting;
				  if (job.colour.sequence == 1)
					  gate.pass();
				  std::this_thread::sleep_for(1ms);
				  // The same setting all through the frame.
				  job.colour.timestampNs = setting == before ? uint64_t(setting) : 0;
			  },
			  [&](KeyingJob &job) {
				  seen.emplace_back(job.colour.sequence, int(job.colour.timestampNs));
				  if (pending) { // between frames: the worker waits for this
					  setting = pending;
					  pending = 0;
				  }
			  }),
		  0);
	ASSERT_TRUE(worker.idle());
	setting = 1; // idle: the loop's to change at once
	submitFrame(worker, 1);
	submitFrame(worker, 2);
	ASSERT_TRUE(gate.waitEntered(1));
	// A reload while frame 1 is keyed and frame 2 waits.
	ASSERT_FALSE(worker.idle());
	pending = 2;
	gate.open();
	// Once idle (an sd-event loop runs once: both steps in one run), the
	// loop changes the setting at once and the next frame sees it.
	bool third = false;
	ASSERT_TRUE(runUntil(loop, [&] {
		if (!worker.idle())
			return false;
		if (third)
			return true;
		setting = 3;
		submitFrame(worker, 3);
		third = true;
		return false;
	}));
	worker.stop();
	const std::vector<std::pair<uint64_t, int>> expected{ { 1, 1 }, { 2, 2 }, { 3, 3 } };
	EXPECT_EQ(seen, expected);
}

TEST(KeyingWorker, StopJoinsAWorkerInTheMiddleOfAFrame)
{
	EventLoop loop;
	ASSERT_EQ(loop.open(), 0);
	KeyingWorker worker;
	Gate gate;
	std::atomic<bool> finished{ false };
	int results = 0;
	ASSERT_EQ(worker.start(
			  loop, 1,
			  [&](KeyingJob &) {
				  gate.pass();
				  std::this_thread::sleep_for(50ms);
				  finished = true;
			  },
			  [&](KeyingJob &) { results++; }),
		  0);
	submitFrame(worker, 1);
	submitFrame(worker, 2); // waits; dropped by stop(), never keyed
	gate.open();
	ASSERT_TRUE(gate.waitEntered(1));
	worker.stop();
	EXPECT_TRUE(finished) << "stop() returned before the frame being keyed was done";
	EXPECT_FALSE(worker.running());
	EXPECT_EQ(worker.nextJob(), nullptr);
	// Nothing comes back after stop: the loop has no source left to call.
	EXPECT_FALSE(runUntil(loop, [&] { return results > 0; }, 50ms));
	EXPECT_EQ(results, 0);
	EXPECT_EQ(worker.dropped(), 0u);
	worker.stop(); // twice is harmless
}

// The "stall" test fault: a keying that waits for stop() is woken by it.
TEST(KeyingWorker, StopWakesAWorkerWaitingForIt)
{
	EventLoop loop;
	ASSERT_EQ(loop.open(), 0);
	KeyingWorker worker;
	Gate gate;
	ASSERT_EQ(worker.start(
			  loop, 1,
			  [&](KeyingJob &) {
				  gate.pass();
				  worker.waitForStop();
			  },
			  [](KeyingJob &) {}),
		  0);
	gate.open();
	submitFrame(worker, 1);
	ASSERT_TRUE(gate.waitEntered(1));
	const auto begin = std::chrono::steady_clock::now();
	worker.stop();
	EXPECT_LT(std::chrono::steady_clock::now() - begin, 2s);
}

TEST(KeyingWorker, DepthIsCopiedSoThePairerMayMoveOn)
{
	DepthFrame before, after;
	before.depthMm = Gray16Image(4, 3, 1000);
	after.depthMm = Gray16Image(4, 3, 2000);
	FramePairer::Bracket bracket;
	bracket.before = &before;
	bracket.after = &after;
	KeyingJob job;
	job.setDepth(bracket);
	before.depthMm = Gray16Image(4, 3, 7); // the pairer's history moved on
	ASSERT_NE(job.depth.before, nullptr);
	EXPECT_EQ(job.depth.before, &job.depthBefore);
	EXPECT_EQ(job.depth.before->depthMm.at(0, 0), 1000);
	EXPECT_EQ(job.depth.after->depthMm.at(0, 0), 2000);
	EXPECT_EQ(job.newestDepth(), &job.depthBefore);
	FramePairer::Bracket none;
	job.setDepth(none);
	EXPECT_EQ(job.newestDepth(), nullptr);
}
