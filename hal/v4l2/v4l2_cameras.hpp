// The V4L2 colour camera (YUYV, NV12, MJPEG -> RGB) and depth camera (Z16,
// Y16 -> mm): the same V4l2Stream with two frame converters.
#pragma once

#include "hal/camera.hpp"
#include "hal/v4l2/mjpeg_decoder.hpp"
#include "hal/v4l2/v4l2_stream.hpp"
#include "settings/settings.hpp"

namespace depthkey {

// The fourccs a colour.pixel_format setting accepts, most preferred first.
std::vector<uint32_t> colourFourccs(const std::string &pixelFormat);

class V4l2ColourCamera : public ColourCamera
{
public:
	// name: "v4l2-colour"; the board's capture stick is the same class as
	// "v4l2-board" (hal/board/board_sources.hpp).
	explicit V4l2ColourCamera(const ColourCameraSettings &settings, std::string name = "v4l2-colour")
		: settings_(settings), name_(std::move(name)) {}
	std::string name() const override { return name_; }
	int start(EventLoop &loop, FrameHandler onFrame, StatusHandler onStatus) override;
	void stop() override { stream_.stop(); }
	DeviceStatus status() const override { return stream_.status(); }

private:
	int convert(const V4l2Buffer &buffer, const V4l2Format &format);

	ColourCameraSettings settings_;
	std::string name_;
	V4l2Stream stream_;
	MjpegDecoder mjpeg_;
	FrameHandler onFrame_;
	ColourFrame frame_;
};

class V4l2DepthCamera : public DepthCamera
{
public:
	explicit V4l2DepthCamera(const DepthCameraSettings &settings) : settings_(settings) {}
	std::string name() const override { return "v4l2-depth"; }
	int start(EventLoop &loop, FrameHandler onFrame, StatusHandler onStatus) override;
	void stop() override { stream_.stop(); }
	DeviceStatus status() const override { return stream_.status(); }

private:
	int convert(const V4l2Buffer &buffer, const V4l2Format &format);

	DepthCameraSettings settings_;
	V4l2Stream stream_;
	uint32_t scaleQ16_ = 0;
	FrameHandler onFrame_;
	DepthFrame frame_;
};

} // namespace depthkey
