#include "hal/v4l2/v4l2_cameras.hpp"

#include "hal/v4l2/depth16_to_frame.hpp"
#include "hal/v4l2/yuv_to_rgb.hpp"

#include <cerrno>
#include <linux/videodev2.h>

namespace depthkey {

std::vector<uint32_t> colourFourccs(const std::string &pixelFormat)
{
	if (pixelFormat == "yuyv")
		return { V4L2_PIX_FMT_YUYV };
	if (pixelFormat == "nv12")
		return { V4L2_PIX_FMT_NV12 };
	if (pixelFormat == "mjpeg")
		return { V4L2_PIX_FMT_MJPEG };
	// auto: uncompressed first (no decoding cost, no artefacts), MJPEG for
	// cameras that offer large sizes only compressed.
	return { V4L2_PIX_FMT_YUYV, V4L2_PIX_FMT_NV12, V4L2_PIX_FMT_MJPEG };
}

int V4l2ColourCamera::start(EventLoop &loop, FrameHandler onFrame, StatusHandler onStatus)
{
	onFrame_ = std::move(onFrame);
	frame_.sequence = 0;
	V4l2StreamConfig config{ settings_.device, colourFourccs(settings_.pixelFormat),
				 settings_.width, settings_.height, settings_.fps,
				 static_cast<uint64_t>(settings_.timeoutMs) * 1000u };
	return stream_.start(
		loop, std::move(config),
		[this](const V4l2Buffer &b, const V4l2Format &f) { return convert(b, f); },
		std::move(onStatus));
}

int V4l2ColourCamera::convert(const V4l2Buffer &b, const V4l2Format &f)
{
	int ret;
	switch (f.fourcc) {
	case V4L2_PIX_FMT_YUYV:
		ret = yuyvToRgb(b.data, b.bytesUsed, f.width, f.height, f.bytesPerLine, frame_.rgb);
		break;
	case V4L2_PIX_FMT_NV12:
		ret = nv12ToRgb(b.data, b.bytesUsed, f.width, f.height, f.bytesPerLine, frame_.rgb);
		break;
	case V4L2_PIX_FMT_MJPEG:
		ret = mjpeg_.decode(b.data, b.bytesUsed, f.width, f.height, frame_.rgb);
		break;
	default:
		ret = -EINVAL;
	}
	if (ret < 0)
		return ret;
	frame_.timestampNs = b.timestampNs;
	frame_.sequence++;
	onFrame_(frame_);
	return 0;
}

int V4l2DepthCamera::start(EventLoop &loop, FrameHandler onFrame, StatusHandler onStatus)
{
	onFrame_ = std::move(onFrame);
	frame_.sequence = 0;
	scaleQ16_ = depthScaleQ16(settings_.scaleMm);
	uint32_t fourcc = settings_.pixelFormat == "y16" ? V4L2_PIX_FMT_Y16 : V4L2_PIX_FMT_Z16;
	V4l2StreamConfig config{ settings_.device, { fourcc }, settings_.width, settings_.height,
				 settings_.fps, static_cast<uint64_t>(settings_.timeoutMs) * 1000u };
	return stream_.start(
		loop, std::move(config),
		[this](const V4l2Buffer &b, const V4l2Format &f) { return convert(b, f); },
		std::move(onStatus));
}

int V4l2DepthCamera::convert(const V4l2Buffer &b, const V4l2Format &f)
{
	int ret = depth16ToFrame(b.data, b.bytesUsed, f.width, f.height, f.bytesPerLine, scaleQ16_,
				 settings_.minMm, settings_.maxMm, frame_);
	if (ret < 0)
		return ret;
	frame_.timestampNs = b.timestampNs;
	frame_.sequence++;
	onFrame_(frame_);
	return 0;
}

} // namespace depthkey
