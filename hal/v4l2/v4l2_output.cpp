#include "hal/v4l2/v4l2_output.hpp"

#include "hal/v4l2/rgb_to_yuyv.hpp"

#include <cerrno>
#include <cstring>

namespace depthkey {

const char *v4l2OutputStateName(DeviceState state)
{
	switch (state) {
	case DeviceState::Streaming:
		return "writing";
	case DeviceState::Lost:
		return "lost";
	case DeviceState::Stopped:
		break;
	}
	return "off";
}

V4l2Output::V4l2Output(std::unique_ptr<VideoOutputDevice> device)
	: device_(device ? std::move(device) : std::make_unique<V4l2OutputDevice>())
{
}

void V4l2Output::start(EventLoop &loop, const std::string &path, StatusHandler onStatus)
{
	loop_ = &loop;
	onStatus_ = std::move(onStatus);
	if (path == path_)
		return;
	stop();
	path_ = path;
	backoff_.reset();
}

void V4l2Output::stop()
{
	retryTimer_.reset();
	device_->close();
	open_ = false;
	path_.clear();
	width_ = height_ = 0;
	setStatus(DeviceState::Stopped, 0, "");
}

void V4l2Output::setStatus(DeviceState state, int error, const std::string &detail)
{
	if (status_.set(state, error, detail) && onStatus_)
		onStatus_(status_);
}

void V4l2Output::tryOpen()
{
	std::string detail;
	const int width = yuyvWidth(width_);
	int ret = device_->open(path_, width, height_, yuyvFrameBytes(width_, height_), detail);
	if (ret < 0) {
		device_->close();
		setStatus(DeviceState::Lost, ret, detail);
		loop_->addTimer(backoff_.nextDelayUs(), [this] { tryOpen(); }, retryTimer_);
		return;
	}
	open_ = true;
	wroteSinceOpen_ = false;
}

void V4l2Output::fail(int error, const std::string &detail)
{
	open_ = false;
	device_->close();
	setStatus(DeviceState::Lost, error, path_ + ": " + detail);
	loop_->addTimer(backoff_.nextDelayUs(), [this] { tryOpen(); }, retryTimer_);
}

int V4l2Output::write(const RgbImage &image)
{
	if (path_.empty() || !loop_ || image.empty())
		return -ENODEV;
	if (image.width() != width_ || image.height() != height_) {
		// A new size (first frame, reload, board geometry): a new format.
		// The retry, if one is pending, would open the old size.
		retryTimer_.reset();
		device_->close();
		open_ = false;
		width_ = image.width();
		height_ = image.height();
		yuyv_.resize(yuyvFrameBytes(width_, height_));
		tryOpen();
	}
	if (!open_)
		return -ENODEV;
	rgbToYuyv(image, yuyv_.data(), yuyv_.size(), kernelPath_);
	ssize_t n = device_->write(yuyv_.data(), yuyv_.size());
	if (n == -EAGAIN || (n >= 0 && static_cast<size_t>(n) < yuyv_.size())) {
		status_.droppedFrames++;
		return -EAGAIN;
	}
	if (n < 0) {
		fail(static_cast<int>(n), std::string("write: ") + std::strerror(static_cast<int>(-n)));
		return static_cast<int>(n);
	}
	written_++;
	if (!wroteSinceOpen_) {
		wroteSinceOpen_ = true;
		backoff_.reset();
		setStatus(DeviceState::Streaming, 0, path_);
	}
	return 0;
}

} // namespace depthkey
