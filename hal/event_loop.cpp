#include "hal/event_loop.hpp"

#include <cerrno>
#include <csignal>
#include <ctime>
#include <systemd/sd-event.h>

namespace depthkey {

EventSource::EventSource(EventSource &&other) noexcept
	: source_(other.source_), handler_(std::move(other.handler_))
{
	other.source_ = nullptr;
}

EventSource &EventSource::operator=(EventSource &&other) noexcept
{
	if (this != &other) {
		reset();
		source_ = other.source_;
		handler_ = std::move(other.handler_);
		other.source_ = nullptr;
	}
	return *this;
}

void EventSource::reset()
{
	if (source_) {
		sd_event_source_disable_unref(source_);
		source_ = nullptr;
	}
	handler_.reset();
}

EventLoop::~EventLoop()
{
	if (event_)
		sd_event_unref(event_);
}

int EventLoop::open()
{
	if (event_)
		return 0;
	return sd_event_new(&event_);
}

namespace {

using Handler = EventSource::Handler;

int dispatchTimer(sd_event_source *s, uint64_t usec, void *userdata)
{
	auto handler = static_cast<Handler *>(userdata)->shared_from_this();
	if (handler->periodUs) {
		// Re-arm before calling back (the callback may destroy the source).
		// A late tick moves the schedule rather than firing a burst.
		timespec ts;
		clock_gettime(CLOCK_MONOTONIC, &ts);
		uint64_t now = static_cast<uint64_t>(ts.tv_sec) * 1000000u + ts.tv_nsec / 1000u;
		uint64_t next = usec + handler->periodUs;
		if (next <= now)
			next = now + handler->periodUs;
		sd_event_source_set_time(s, next);
		sd_event_source_set_enabled(s, SD_EVENT_ON);
	}
	handler->callback(0);
	return 0;
}

int dispatchIo(sd_event_source *, int, uint32_t revents, void *userdata)
{
	auto handler = static_cast<Handler *>(userdata)->shared_from_this();
	handler->callback(revents);
	return 0;
}

int dispatchSignal(sd_event_source *, const struct signalfd_siginfo *, void *userdata)
{
	auto handler = static_cast<Handler *>(userdata)->shared_from_this();
	handler->callback(0);
	return 0;
}

int dispatchPost(sd_event_source *, void *userdata)
{
	auto handler = static_cast<Handler *>(userdata)->shared_from_this();
	handler->callback(0);
	return 0;
}

std::function<void(uint32_t)> ignoreArgument(std::function<void()> callback)
{
	return [cb = std::move(callback)](uint32_t) { cb(); };
}

} // namespace

int EventLoop::addTimer(uint64_t delayUs, std::function<void()> callback, EventSource &source)
{
	source.reset();
	source.handler_ = std::make_shared<Handler>(ignoreArgument(std::move(callback)), 0);
	int ret = sd_event_add_time_relative(event_, &source.source_, CLOCK_MONOTONIC, delayUs,
					     1000, dispatchTimer, source.handler_.get());
	if (ret < 0)
		source.reset();
	return ret;
}

int EventLoop::addPeriodic(uint64_t periodUs, std::function<void()> callback, EventSource &source)
{
	if (periodUs == 0)
		return -EINVAL;
	source.reset();
	source.handler_ = std::make_shared<Handler>(ignoreArgument(std::move(callback)), periodUs);
	int ret = sd_event_add_time_relative(event_, &source.source_, CLOCK_MONOTONIC, periodUs,
					     1000, dispatchTimer, source.handler_.get());
	if (ret < 0)
		return source.reset(), ret;
	return sd_event_source_set_enabled(source.source_, SD_EVENT_ON);
}

int EventLoop::addIo(int fd, uint32_t events, std::function<void(uint32_t)> callback, EventSource &source)
{
	source.reset();
	source.handler_ = std::make_shared<Handler>(std::move(callback), 0);
	int ret = sd_event_add_io(event_, &source.source_, fd, events, dispatchIo,
				  source.handler_.get());
	if (ret < 0)
		source.reset();
	return ret;
}

int EventLoop::addSignal(int signal, std::function<void()> callback, EventSource &source)
{
	source.reset();
	source.handler_ = std::make_shared<Handler>(ignoreArgument(std::move(callback)), 0);
	int ret = sd_event_add_signal(event_, &source.source_, signal, dispatchSignal,
				      source.handler_.get());
	if (ret < 0)
		source.reset();
	return ret;
}

int EventLoop::addPost(std::function<void()> callback, EventSource &source)
{
	source.reset();
	source.handler_ = std::make_shared<Handler>(ignoreArgument(std::move(callback)), 0);
	int ret = sd_event_add_post(event_, &source.source_, dispatchPost, source.handler_.get());
	if (ret < 0)
		return source.reset(), ret;
	// A post source is one-shot by default; keep it for every iteration.
	return sd_event_source_set_enabled(source.source_, SD_EVENT_ON);
}

int EventLoop::run()
{
	return sd_event_loop(event_);
}

void EventLoop::exit(int code)
{
	sd_event_exit(event_, code);
}

uint64_t EventLoop::nowUs() const
{
	timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return static_cast<uint64_t>(ts.tv_sec) * 1000000u + static_cast<uint64_t>(ts.tv_nsec) / 1000u;
}

int EventLoop::blockSignals(std::initializer_list<int> signals)
{
	sigset_t set;
	sigemptyset(&set);
	for (int s : signals)
		sigaddset(&set, s);
	if (sigprocmask(SIG_BLOCK, &set, nullptr) < 0)
		return -errno;
	return 0;
}

} // namespace depthkey
