#include "hal/background_job.hpp"

#include <pthread.h>
#include <cerrno>
#include <sys/epoll.h>
#include <sys/eventfd.h>
#include <system_error>
#include <unistd.h>

namespace depthkey {

BackgroundJob::~BackgroundJob()
{
	if (thread_.joinable())
		thread_.join();
	source_.reset();
}

int BackgroundJob::start(EventLoop &loop, std::function<void()> work, std::function<void()> done)
{
	if (running_)
		return -EBUSY;
	if (!eventFd_.isValid()) {
		eventFd_.reset(eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC));
		if (!eventFd_.isValid())
			return -errno;
	}
	if (!source_.active()) {
		int ret = loop.addIo(eventFd_.get(), EPOLLIN, [this](uint32_t) { finish(); }, source_);
		if (ret < 0)
			return ret;
	}
	done_ = std::move(done);
	try {
		// The eventfd write is the release: done() sees all work() wrote.
		thread_ = std::thread([this, work = std::move(work)] {
			pthread_setname_np(pthread_self(), "dk-job"); // for top -H and make bench-process
			work();
			uint64_t one = 1;
			(void)!::write(eventFd_.get(), &one, sizeof(one));
		});
	} catch (const std::system_error &e) {
		return -(e.code().value() ? e.code().value() : EAGAIN);
	}
	running_ = true;
	return 0;
}

void BackgroundJob::finish()
{
	uint64_t count;
	if (::read(eventFd_.get(), &count, sizeof(count)) < 0)
		return; // spurious wake-up: the worker has not written yet
	thread_.join();
	running_ = false;
	auto done = std::move(done_);
	done_ = nullptr;
	if (done)
		done();
}

} // namespace depthkey
