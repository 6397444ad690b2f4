// Drives a libusb context from the daemon's sd-event loop: libusb's file
// descriptors become EventLoop I/O sources (kept in step through the pollfd
// notifiers) and its next timeout becomes a timer; both handle events with a
// zero timeout, so libusb never blocks the loop. Asynchronous transfers then
// complete from inside the loop like any other event.
#pragma once

#include "hal/event_loop.hpp"

#include <map>

struct libusb_context;

namespace depthkey {

class UsbEventBridge
{
public:
	UsbEventBridge() = default;
	~UsbEventBridge() { close(); }
	UsbEventBridge(const UsbEventBridge &) = delete;
	UsbEventBridge &operator=(const UsbEventBridge &) = delete;

	int open(EventLoop &loop); // negative errno (libusb error mapped)
	void close();
	libusb_context *context() { return context_; }

	// Handles whatever is ready now and re-arms the timeout timer. Call it
	// after submitting a transfer too, so its timeout is scheduled.
	void handleEvents();
	// Blocks up to timeoutMs handling events: only for stop(), where
	// cancelled transfers must complete before their memory is freed.
	void handleEventsBlocking(int timeoutMs);

private:
	static void fdAdded(int fd, short events, void *user);
	static void fdRemoved(int fd, void *user);
	void watch(int fd, short events);
	void armTimeout();

	EventLoop *loop_ = nullptr;
	libusb_context *context_ = nullptr;
	std::map<int, EventSource> fds_;
	EventSource timer_;
	bool timeoutsOnFd_ = false; // Linux: libusb's timerfd is one of the fds
};

// libusb error codes -> negative errno, so backends report one kind of error.
int usbErrno(int libusbError);

} // namespace depthkey
