#include "daemon/keying_worker.hpp"

#include <pthread.h>
#include <algorithm>
#include <cerrno>
#include <chrono>
#include <sys/epoll.h>
#include <sys/eventfd.h>
#include <system_error>

namespace depthkey {

void KeyingJob::setDepth(const FramePairer::Bracket &bracket)
{
	depth = bracket;
	if (bracket.before) {
		depthBefore = *bracket.before; // same size: the vectors keep their storage
		depth.before = &depthBefore;
	}
	if (bracket.after) {
		depthAfter = *bracket.after;
		depth.after = &depthAfter;
	}
}

int KeyingWorker::start(EventLoop &loop, size_t capacity, KeyFunction key, ResultFunction result)
{
	stop();
	loop_ = &loop;
	key_ = std::move(key);
	result_ = std::move(result);
	capacity_ = std::clamp<size_t>(capacity, 1, kMaxCapacity);
	states_.fill(State::Free);
	stop_ = false;
	eventFd_ = UniqueFd(eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK));
	if (!eventFd_.isValid())
		return -errno;
	int ret = loop.addIo(eventFd_.get(), EPOLLIN, [this](uint32_t) { takeResult(); }, eventSource_);
	if (ret < 0)
		return ret;
	try {
		thread_ = std::thread([this] { run(); });
	} catch (const std::system_error &e) {
		eventSource_.reset();
		return -(e.code().value() ? e.code().value() : EAGAIN);
	}
	return 0;
}

void KeyingWorker::stop()
{
	{
		std::lock_guard lock(mutex_);
		stop_ = true;
	}
	workerWake_.notify_all();
	loopWake_.notify_all();
	if (thread_.joinable())
		thread_.join();
	eventSource_.reset();
	eventFd_.reset();
	states_.fill(State::Free); // the worker is gone: nothing is shared any more
}

void KeyingWorker::run()
{
	// Named, so that top -H and make bench-process tell keying from the loop.
	pthread_setname_np(pthread_self(), "dk-keying");
	std::unique_lock lock(mutex_);
	for (;;) {
		// The next waiting job, the oldest, once the loop took the last result.
		int next = -1;
		workerWake_.wait(lock, [&] {
			if (stop_)
				return true;
			next = -1;
			for (size_t i = 0; i < states_.size(); ++i) {
				if (states_[i] == State::Done)
					return false;
				if (states_[i] == State::Waiting && (next < 0 || order_[i] < order_[size_t(next)]))
					next = int(i);
			}
			return next >= 0;
		});
		if (stop_)
			return;
		states_[size_t(next)] = State::Keying;
		lock.unlock();
		loopWake_.notify_all();

		KeyingJob &job = jobs_[size_t(next)];
		const auto begin = std::chrono::steady_clock::now();
		key_(job);
		job.keyingUs = uint64_t(
			std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::now() - begin)
				.count());

		lock.lock();
		states_[size_t(next)] = State::Done;
		const uint64_t one = 1;
		// A full counter (never, at one a frame) is readable anyway.
		(void)!::write(eventFd_.get(), &one, sizeof(one));
		loopWake_.notify_all();
	}
}

void KeyingWorker::takeResult()
{
	uint64_t count;
	(void)!::read(eventFd_.get(), &count, sizeof(count));
	int done = -1;
	{
		std::lock_guard lock(mutex_);
		for (size_t i = 0; i < states_.size(); ++i)
			if (states_[i] == State::Done)
				done = int(i);
	}
	if (done < 0)
		return;
	// The worker waits while a job is Done: the job, the pipeline and its
	// output are the loop's until the state changes below.
	result_(jobs_[size_t(done)]);
	{
		std::lock_guard lock(mutex_);
		states_[size_t(done)] = State::Free;
	}
	workerWake_.notify_one();
}

int KeyingWorker::freeJob() const
{
	for (size_t i = 0; i < capacity_ + 1; ++i)
		if (states_[i] == State::Free)
			return int(i);
	return -1;
}

size_t KeyingWorker::waitingCount() const
{
	return size_t(std::count(states_.begin(), states_.end(), State::Waiting));
}

KeyingJob *KeyingWorker::nextJob(bool mayDrop)
{
	if (!running())
		return nullptr;
	std::unique_lock lock(mutex_);
	int free = freeJob();
	while (free < 0 && !mayDrop && !stop_) {
		// Only the loop takes results, and the worker keys the next
		// job only after it did: take it here, or wait for the worker.
		bool done = std::find(states_.begin(), states_.end(), State::Done) != states_.end();
		if (done) {
			lock.unlock();
			takeResult();
			lock.lock();
		} else {
			loopWake_.wait(lock);
		}
		free = freeJob();
	}
	if (free >= 0)
		return &jobs_[size_t(free)];
	// The worker is behind: the oldest waiting frame goes, the newest are
	// the ones worth keying.
	int oldest = -1;
	for (size_t i = 0; i < capacity_ + 1; ++i)
		if (states_[i] == State::Waiting && (oldest < 0 || order_[i] < order_[size_t(oldest)]))
			oldest = int(i);
	if (oldest < 0) // never: capacity + 1 jobs, at most one not waiting
		return nullptr;
	states_[size_t(oldest)] = State::Free;
	dropped_++;
	return &jobs_[size_t(oldest)];
}

void KeyingWorker::submit(KeyingJob *job)
{
	if (!job)
		return;
	{
		std::lock_guard lock(mutex_);
		const size_t i = size_t(job - jobs_.data());
		job->submittedSequence = ++submitted_;
		order_[i] = submitted_;
		states_[i] = State::Waiting;
	}
	workerWake_.notify_one();
}

bool KeyingWorker::idle() const
{
	std::lock_guard lock(mutex_);
	return std::all_of(states_.begin(), states_.end(), [](State s) { return s == State::Free; });
}

bool KeyingWorker::full() const
{
	std::lock_guard lock(mutex_);
	return freeJob() < 0;
}

void KeyingWorker::waitForStop()
{
	std::unique_lock lock(mutex_);
	workerWake_.wait(lock, [this] { return stop_; });
}

} // namespace depthkey
