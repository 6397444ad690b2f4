#include "hal/usb/usb_event_bridge.hpp"

#include <cerrno>
#include <libusb.h>
#include <poll.h>
#include <sys/epoll.h>

namespace depthkey {

int usbErrno(int e)
{
	switch (e) {
	case LIBUSB_SUCCESS:
		return 0;
	case LIBUSB_ERROR_IO:
		return -EIO;
	case LIBUSB_ERROR_INVALID_PARAM:
		return -EINVAL;
	case LIBUSB_ERROR_ACCESS:
		return -EACCES;
	case LIBUSB_ERROR_NO_DEVICE:
		return -ENODEV;
	case LIBUSB_ERROR_NOT_FOUND:
		return -ENOENT;
	case LIBUSB_ERROR_BUSY:
		return -EBUSY;
	case LIBUSB_ERROR_TIMEOUT:
		return -ETIMEDOUT;
	case LIBUSB_ERROR_OVERFLOW:
		return -EOVERFLOW;
	case LIBUSB_ERROR_PIPE:
		return -EPIPE;
	case LIBUSB_ERROR_INTERRUPTED:
		return -EINTR;
	case LIBUSB_ERROR_NO_MEM:
		return -ENOMEM;
	case LIBUSB_ERROR_NOT_SUPPORTED:
		return -ENOTSUP;
	default:
		return -EIO;
	}
}

int UsbEventBridge::open(EventLoop &loop)
{
	if (context_)
		return 0;
	loop_ = &loop;
	int ret = libusb_init(&context_);
	if (ret < 0) {
		context_ = nullptr;
		return usbErrno(ret);
	}
	libusb_set_option(context_, LIBUSB_OPTION_LOG_LEVEL, LIBUSB_LOG_LEVEL_NONE);
	timeoutsOnFd_ = libusb_pollfds_handle_timeouts(context_) != 0;
	libusb_set_pollfd_notifiers(context_, fdAdded, fdRemoved, this);
	const libusb_pollfd **fds = libusb_get_pollfds(context_);
	if (!fds) {
		close();
		return -ENOMEM;
	}
	for (const libusb_pollfd **p = fds; *p; ++p)
		watch((*p)->fd, (*p)->events);
	libusb_free_pollfds(fds);
	return 0;
}

void UsbEventBridge::close()
{
	if (!context_)
		return;
	// No callbacks into this object while libusb tears down its fds.
	libusb_set_pollfd_notifiers(context_, nullptr, nullptr, nullptr);
	fds_.clear();
	timer_.reset();
	libusb_exit(context_);
	context_ = nullptr;
}

void UsbEventBridge::fdAdded(int fd, short events, void *user)
{
	static_cast<UsbEventBridge *>(user)->watch(fd, events);
}

void UsbEventBridge::fdRemoved(int fd, void *user)
{
	// Safe from inside that fd's own callback: EventSource keeps the
	// running handler alive until it returns.
	static_cast<UsbEventBridge *>(user)->fds_.erase(fd);
}

void UsbEventBridge::watch(int fd, short events)
{
	uint32_t epoll = (events & POLLIN ? uint32_t(EPOLLIN) : 0u) |
			 (events & POLLOUT ? uint32_t(EPOLLOUT) : 0u);
	EventSource &source = fds_[fd];
	if (loop_->addIo(fd, epoll, [this](uint32_t) { handleEvents(); }, source) < 0)
		fds_.erase(fd);
}

void UsbEventBridge::handleEvents()
{
	if (!context_)
		return;
	timeval zero = { 0, 0 };
	libusb_handle_events_timeout_completed(context_, &zero, nullptr);
	armTimeout();
}

void UsbEventBridge::handleEventsBlocking(int timeoutMs)
{
	if (!context_)
		return;
	timeval tv = { timeoutMs / 1000, (timeoutMs % 1000) * 1000 };
	libusb_handle_events_timeout_completed(context_, &tv, nullptr);
}

void UsbEventBridge::armTimeout()
{
	if (timeoutsOnFd_ || !context_)
		return;
	timeval tv;
	int ret = libusb_get_next_timeout(context_, &tv);
	if (ret <= 0) {
		timer_.reset();
		return;
	}
	uint64_t us = static_cast<uint64_t>(tv.tv_sec) * 1000000u + tv.tv_usec;
	loop_->addTimer(us, [this] { handleEvents(); }, timer_);
}

} // namespace depthkey
