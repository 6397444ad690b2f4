#include "hal/sim/sim_render_thread.hpp"

#include <pthread.h>
#include <cerrno>
#include <sys/epoll.h>
#include <sys/eventfd.h>
#include <system_error>
#include <unistd.h>

namespace depthkey {

int SimRenderThread::start(EventLoop &loop, const char *name, std::function<void()> render,
			   std::function<void()> rendered)
{
	stop();
	render_ = std::move(render);
	rendered_ = std::move(rendered);
	state_ = State::Idle;
	stop_ = false;
	eventFd_.reset(eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK));
	if (!eventFd_.isValid())
		return -errno;
	int ret = loop.addIo(eventFd_.get(), EPOLLIN, [this](uint32_t) { deliverFinished(); }, eventSource_);
	if (ret < 0) {
		eventFd_.reset();
		return ret;
	}
	try {
		thread_ = std::thread([this] { run(); });
	} catch (const std::system_error &e) {
		eventSource_.reset();
		eventFd_.reset();
		return -(e.code().value() ? e.code().value() : EAGAIN);
	}
	// Named here rather than by the thread: it has its name once start()
	// returns (top -H, make bench-process, the share test's cgroup move).
	pthread_setname_np(thread_.native_handle(), name);
	return 0;
}

void SimRenderThread::stop()
{
	{
		std::lock_guard lock(mutex_);
		stop_ = true;
	}
	wake_.notify_all();
	if (thread_.joinable())
		thread_.join(); // after the render in progress, if any
	eventSource_.reset();
	eventFd_.reset();
	state_ = State::Idle; // the thread is gone: a finished frame is not delivered
}

void SimRenderThread::run()
{
	std::unique_lock lock(mutex_);
	for (;;) {
		wake_.wait(lock, [this] { return stop_ || state_ == State::Asked; });
		if (stop_)
			return;
		state_ = State::Rendering;
		lock.unlock();
		render_();
		lock.lock();
		state_ = State::Rendered;
		const uint64_t one = 1;
		(void)!::write(eventFd_.get(), &one, sizeof(one));
	}
}

void SimRenderThread::deliverFinished()
{
	{
		std::lock_guard lock(mutex_);
		if (state_ != State::Rendered)
			return; // still rendering, or delivered already (by a tick before this wake-up)
		state_ = State::Idle;
	}
	uint64_t count;
	(void)!::read(eventFd_.get(), &count, sizeof(count)); // this wake-up is used up
	rendered_();
}

bool SimRenderThread::busy() const
{
	std::lock_guard lock(mutex_);
	return state_ == State::Asked || state_ == State::Rendering;
}

void SimRenderThread::begin()
{
	{
		std::lock_guard lock(mutex_);
		if (state_ != State::Idle || !thread_.joinable())
			return;
		state_ = State::Asked;
	}
	wake_.notify_one();
}

} // namespace depthkey
