// Where a simulated camera renders its frames (issue 29 §2): a thread of its
// own, named (dk-sim-colour, dk-sim-depth, dk-sim-board) so that top -H,
// make bench-process and the CPU-share test tell the simulator's rendering
// apart from the event loop. On the box a camera fills its frame by DMA: the
// stand-in's rendering is not the box's cost and must not count against the
// daemon's CPU share, which it did while it ran in the loop's timer.
//
// One render at a time. The loop asks for one (begin()); the thread renders;
// the finished frame comes back to the loop through an eventfd the loop
// watches (as daemon/keying_worker.hpp does), and the loop delivers it
// (the rendered callback). Between begin() and the delivery, whatever the
// render function reads and writes belongs to the thread; otherwise to the
// loop. The mutex hands it over (happens-before both ways).
#pragma once

#include "hal/event_loop.hpp"
#include "hal/unique_fd.hpp"

#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>

namespace depthkey {

class SimRenderThread
{
public:
	SimRenderThread() = default;
	~SimRenderThread() { stop(); }
	SimRenderThread(const SimRenderThread &) = delete;
	SimRenderThread &operator=(const SimRenderThread &) = delete;

	// Starts the thread, named name (15 characters at most: the kernel's
	// limit). render runs on it for each begin(); rendered on the loop's
	// thread after it. A negative errno when the eventfd, its loop source
	// or the thread cannot be had. Stops a thread already running first.
	int start(EventLoop &loop, const char *name, std::function<void()> render, std::function<void()> rendered);
	// Waits for a render in progress (one frame's work: bounded), drops its
	// result undelivered and joins the thread. Safe to call twice.
	void stop();

	// Loop only. Delivers a finished render whose eventfd wake-up the loop
	// has not dispatched yet (a tick may come first): call before begin().
	void deliverFinished();
	// Loop only: a render asked for has not finished: a new one must wait.
	bool busy() const;
	// Loop only: asks for a render (not busy(), after deliverFinished()).
	void begin();

private:
	enum class State { Idle, Asked, Rendering, Rendered };
	void run();

	std::function<void()> render_, rendered_;
	UniqueFd eventFd_; // declared before eventSource_: closed after it leaves the loop
	EventSource eventSource_;
	std::thread thread_;
	mutable std::mutex mutex_;
	std::condition_variable wake_; // asked, or stop
	State state_ = State::Idle;
	bool stop_ = false;
};

} // namespace depthkey
