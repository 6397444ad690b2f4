// The virtual webcam: the composite written to a v4l2loopback device
// (output.v4l2_device) as YUYV, so that OBS, ffmpeg, browsers and
// video-call programs see it as an ordinary camera.
//
// write() is called with each published composite on the event loop and
// never waits: the frame is converted into a buffer allocated once per size
// and written with one non-blocking write(); a device that takes nothing
// (-EAGAIN) loses that frame, counted. A device that vanishes or fails is
// closed, reported Lost, and re-opened after the cameras' backoff
// (hal/reconnect_backoff.hpp) on a timer; frames meanwhile are not written.
// It is Streaming ("writing") from its first frame written after an open.
#pragma once

#include "algo/image.hpp"
#include "hal/camera.hpp"
#include "hal/event_loop.hpp"
#include "hal/kernel_path_env.hpp"
#include "hal/reconnect_backoff.hpp"
#include "hal/v4l2/video_output_device.hpp"

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace depthkey {

// "writing", "lost", or "off" (no device configured, or waiting for a frame).
const char *v4l2OutputStateName(DeviceState state);

class V4l2Output
{
public:
	using StatusHandler = std::function<void(const DeviceStatus &)>;

	// device: the backend (null = the real V4l2OutputDevice). Opens nothing.
	explicit V4l2Output(std::unique_ptr<VideoOutputDevice> device = nullptr);
	~V4l2Output()
	{
		onStatus_ = nullptr; // its owner may be half destroyed
		stop();
	}
	V4l2Output(const V4l2Output &) = delete;
	V4l2Output &operator=(const V4l2Output &) = delete;

	// Writes to path from the next frame on ("" = off). onStatus hears every
	// change of state or error (not the drop counter). Calling it again with
	// another path closes the old device; with the same path it does nothing.
	void start(EventLoop &loop, const std::string &path, StatusHandler onStatus);
	void stop();

	// One composite. 0: written; -EAGAIN: the device was full, frame dropped
	// (counted); -ENODEV while lost or off; another negative errno: the device
	// failed now and is being re-opened. A new size re-opens the device.
	int write(const RgbImage &image);

	bool enabled() const { return !path_.empty(); }
	const std::string &path() const { return path_; }
	// state, last error and detail; droppedFrames = frames the device refused
	// (-EAGAIN or a short write).
	const DeviceStatus &status() const { return status_; }
	uint64_t framesWritten() const { return written_; }
	// The conversion's rows: SSE2 unless DEPTHKEY_FORCE_C=1 (hal/kernel_path_env.hpp).
	void setKernelPath(KernelPath path) { kernelPath_ = path; }

private:
	void tryOpen();
	void fail(int error, const std::string &detail);
	void setStatus(DeviceState state, int error, const std::string &detail);

	std::unique_ptr<VideoOutputDevice> device_;
	EventLoop *loop_ = nullptr;
	std::string path_;
	StatusHandler onStatus_;
	EventSource retryTimer_;
	ReconnectBackoff backoff_;
	DeviceStatus status_;
	bool open_ = false;
	bool wroteSinceOpen_ = false;
	int width_ = 0, height_ = 0; // of the frames; the device's width is yuyvWidth(width_)
	std::vector<uint8_t> yuyv_;  // one frame, resized only when the size changes
	uint64_t written_ = 0;
	KernelPath kernelPath_ = kernelPathFromEnvironment();
};

} // namespace depthkey
