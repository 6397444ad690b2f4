// Keying off the event loop (issue 28): the loop pairs colour frames with
// depth and hands each over here; one worker thread keys it; the result
// comes back to the loop through an eventfd the loop watches, and the loop
// publishes it. The loop never waits for keying, so a frame that takes
// longer than a colour period no longer holds up the watchdog, the depth
// camera's USB steps, the preview, reloads or a device's reconnection.
//
// Jobs: a fixed pool of capacity + 1, each with its colour frame, the depth
// frames around it and what keying needs to know, allocated at their sizes
// by the first frames and reused (no allocation per frame in steady state).
// A job is free, waiting (at most capacity, in arrival order), being keyed,
// or done (its result not yet taken by the loop). The loop fills a free job
// and submits it; when the worker is behind and none is free, the oldest
// waiting job is dropped and counted (dropped()): the newest frames are the
// ones worth keying. That is the backpressure that replaced the token
// bucket of loop time (daemon/keying_budget.hpp, removed).
//
// What keying reads and writes (the pipeline, its output, the board picture
// it samples) belongs to whoever holds it: the worker while a job is being
// keyed, the loop otherwise. The worker takes the next waiting job only
// after the loop took the previous result, so the loop reads the result
// (the pipeline's stage images, its alpha) while publishing without a copy,
// and changes the pipeline (a reload, a new board picture) between frames:
// when idle(), or from the result callback. One mutex guards the job states
// and hands the jobs' contents over (happens-before both ways).
//
// Results come back in submission order: one worker, one queue.
#pragma once

#include "algo/frame_pairer.hpp"
#include "algo/frames.hpp"
#include "hal/event_loop.hpp"
#include "hal/unique_fd.hpp"

#include <array>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <thread>

namespace depthkey {

struct KeyingJob {
	ColourFrame colour;
	// The depth frames around it (copied: the pairer's history moves on
	// while the job waits; same size, so no allocation after the first).
	DepthFrame depthBefore, depthAfter;
	FramePairer::Bracket depth; // points into depthBefore/depthAfter, or null
	bool makeComposite = true;  // Pipeline::setMakeComposite for this frame
	uint64_t submittedSequence = 0; // the order it was submitted in (tests)
	uint64_t keyingUs = 0;      // measured on the worker

	// Copies the depth frames of a bracket in and points depth at them.
	void setDepth(const FramePairer::Bracket &bracket);
	const DepthFrame *newestDepth() const { return depth.before ? depth.before : depth.after; }
};

class KeyingWorker
{
public:
	static constexpr size_t kMaxCapacity = 4;
	// Runs on the worker: keys the job.
	using KeyFunction = std::function<void(KeyingJob &)>;
	// Runs on the loop: the job's result, in submission order. The worker
	// waits until it returns before it keys the next job.
	using ResultFunction = std::function<void(KeyingJob &)>;

	KeyingWorker() = default;
	~KeyingWorker() { stop(); }
	KeyingWorker(const KeyingWorker &) = delete;
	KeyingWorker &operator=(const KeyingWorker &) = delete;

	// capacity: jobs that may wait for the worker (1..kMaxCapacity). A
	// negative errno when the eventfd, its loop source or the thread cannot
	// be made.
	int start(EventLoop &loop, size_t capacity, KeyFunction key, ResultFunction result);
	// Joins the worker: a job being keyed is finished first; waiting jobs
	// and a result not yet taken are dropped (not counted: the daemon is
	// stopping). Safe to call twice.
	void stop();
	bool running() const { return thread_.joinable(); }

	// Loop only. The job to fill for the next frame. A full pool drops its
	// oldest waiting job (counted) when mayDrop; otherwise (a source that
	// waits for the daemon: a replay not in real time) the loop waits for
	// the worker, taking its results meanwhile: the one case it does.
	// Null when not running.
	KeyingJob *nextJob(bool mayDrop = true);
	// Loop only: hands the job nextJob() gave over to the worker.
	void submit(KeyingJob *job);
	// Loop only: no job waiting, being keyed or done: what keying uses is
	// the loop's to change now.
	bool idle() const;
	// Loop only: whether nextJob(true) would drop a waiting job now.
	bool full() const;
	// Jobs dropped because the worker was behind.
	uint64_t dropped() const { return dropped_; }

	// Worker only (from the key function): blocks until stop(). The "stall"
	// test fault: a wedged keying stops publication, not the loop.
	void waitForStop();

private:
	enum class State { Free, Waiting, Keying, Done };
	void run();
	// Loop: takes a finished job's result, if any.
	void takeResult();
	int freeJob() const;      // under mutex_
	size_t waitingCount() const; // under mutex_

	EventLoop *loop_ = nullptr;
	KeyFunction key_;
	ResultFunction result_;
	UniqueFd eventFd_;
	EventSource eventSource_;
	std::thread thread_;

	mutable std::mutex mutex_;
	std::condition_variable workerWake_; // a job waits, the result was taken, stop
	std::condition_variable loopWake_;   // a job was taken or finished (nextJob without dropping)
	std::array<KeyingJob, kMaxCapacity + 1> jobs_;
	std::array<State, kMaxCapacity + 1> states_{};
	std::array<uint64_t, kMaxCapacity + 1> order_{}; // submission order of waiting jobs
	size_t capacity_ = 1;
	uint64_t submitted_ = 0;
	bool stop_ = false;
	uint64_t dropped_ = 0; // loop only
};

} // namespace depthkey
