// One V4L2 capture stream that never gives up, shared by the colour and the
// depth camera (they differ only in the formats they ask for and in how a
// buffer becomes a frame). It negotiates the format, streams with mmap
// buffers, dequeues when the event loop says the fd is readable, and on
// EIO/ENODEV/POLLERR or no frame within the timeout it closes the device,
// reports Lost and re-opens with backoff; Streaming once a frame converts.
#pragma once

#include "hal/camera.hpp"
#include "hal/reconnect_backoff.hpp"
#include "hal/v4l2/v4l2_video_device.hpp"

#include <functional>
#include <string>
#include <vector>

namespace depthkey {

struct V4l2StreamConfig {
	std::string device;             // absolute path, or a name in /dev/v4l/by-id/
	std::vector<uint32_t> fourccs;  // acceptable formats, most preferred first
	int width = 0;
	int height = 0;
	int fps = 0;
	uint64_t timeoutUs = 1'000'000; // no frame this long: stalled
};

// "/dev/video0" stays, "usb-Logitech_C920-video-index0" -> /dev/v4l/by-id/...
std::string resolveVideoDevice(const std::string &device);

// Picks the first of wanted that the device offers; 0 if none.
uint32_t chooseFourcc(const std::vector<uint32_t> &wanted, const std::vector<uint32_t> &offered);

class V4l2Stream
{
public:
	// Turns a filled buffer into a frame and delivers it; a negative errno
	// means the buffer was unusable (it is counted as dropped).
	using BufferHandler = std::function<int(const V4l2Buffer &, const V4l2Format &)>;
	using StatusHandler = std::function<void(const DeviceStatus &)>;

	~V4l2Stream() { stop(); }

	int start(EventLoop &loop, V4l2StreamConfig config, BufferHandler onBuffer,
		  StatusHandler onStatus);
	void stop();
	const DeviceStatus &status() const { return status_; }

private:
	void tryOpen();
	int openDevice(std::string &detail);
	void onReadable(uint32_t revents);
	void onWatchdog();
	void fail(int error, const std::string &detail);
	void setStatus(DeviceState state, int error, const std::string &detail);

	EventLoop *loop_ = nullptr;
	V4l2StreamConfig config_;
	BufferHandler onBuffer_;
	StatusHandler onStatus_;
	DeviceStatus status_;
	V4l2VideoDevice device_;
	V4l2Format format_;
	EventSource io_, retryTimer_, watchdog_;
	ReconnectBackoff backoff_;
	StallDetector stall_;
	bool open_ = false;
	bool delivered_ = false; // a frame converted since the last open
};

} // namespace depthkey
