#include "hal/v4l2/video_output_device.hpp"

#include "hal/v4l2/query_capabilities_error.hpp"
#include "hal/v4l2/v4l2_video_device.hpp"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <linux/videodev2.h>
#include <sys/ioctl.h>
#include <unistd.h>
#include <utility>

namespace depthkey {

namespace {

int ioctlRetry(int fd, unsigned long request, void *arg)
{
	int ret;
	do
		ret = ::ioctl(fd, request, arg);
	while (ret < 0 && errno == EINTR);
	return ret < 0 ? -errno : ret;
}

} // namespace

int V4l2OutputDevice::open(const std::string &path, int width, int height, size_t frameBytes,
			   std::string &detail)
{
	close();
	auto failed = [&](const char *step, int ret) {
		detail = path + ": " + step + ": " + std::strerror(-ret);
		return ret;
	};
	UniqueFd fd(::open(path.c_str(), O_RDWR | O_NONBLOCK | O_CLOEXEC));
	if (!fd.isValid())
		return failed("open", -errno);
	v4l2_capability cap = {};
	int ret = queryCapabilitiesError(ioctlRetry(fd.get(), VIDIOC_QUERYCAP, &cap));
	if (ret < 0)
		return failed("not a V4L2 device (query capabilities)", ret);
	uint32_t caps = cap.capabilities & V4L2_CAP_DEVICE_CAPS ? cap.device_caps : cap.capabilities;
	if (!(caps & V4L2_CAP_VIDEO_OUTPUT)) {
		detail = path + " (" + std::string(reinterpret_cast<const char *>(cap.card),
						   strnlen(reinterpret_cast<const char *>(cap.card), sizeof(cap.card))) +
			 ") is not a video output: is it a v4l2loopback device?";
		return -ENODEV;
	}
	v4l2_format f = {};
	f.type = V4L2_BUF_TYPE_VIDEO_OUTPUT;
	f.fmt.pix.width = static_cast<uint32_t>(width);
	f.fmt.pix.height = static_cast<uint32_t>(height);
	f.fmt.pix.pixelformat = V4L2_PIX_FMT_YUYV;
	f.fmt.pix.field = V4L2_FIELD_NONE;
	f.fmt.pix.bytesperline = static_cast<uint32_t>(width) * 2;
	f.fmt.pix.sizeimage = static_cast<uint32_t>(frameBytes);
	f.fmt.pix.colorspace = V4L2_COLORSPACE_SMPTE170M; // BT.601, limited range
	if ((ret = ioctlRetry(fd.get(), VIDIOC_S_FMT, &f)) < 0)
		return failed("set format YUYV", ret);
	// v4l2loopback rounds sizeimage up to whole pages (640x360 YUYV: 462848
	// for 460800); the rows must be packed as ours are, and a frame is one
	// write of frameBytes, which readers take as the frame.
	if (f.fmt.pix.pixelformat != V4L2_PIX_FMT_YUYV || f.fmt.pix.width != static_cast<uint32_t>(width) ||
	    f.fmt.pix.height != static_cast<uint32_t>(height) ||
	    f.fmt.pix.bytesperline != static_cast<uint32_t>(width) * 2 || f.fmt.pix.sizeimage < frameBytes) {
		detail = path + " takes " + fourccName(f.fmt.pix.pixelformat) + " " + std::to_string(f.fmt.pix.width) +
			 "x" + std::to_string(f.fmt.pix.height) + " (" + std::to_string(f.fmt.pix.bytesperline) +
			 " bytes a row, " + std::to_string(f.fmt.pix.sizeimage) + " a frame), not YUYV " +
			 std::to_string(width) + "x" + std::to_string(height) +
			 ": another program holds it in another format?";
		return -EINVAL;
	}
	fd_ = std::move(fd);
	detail = path;
	return 0;
}

ssize_t V4l2OutputDevice::write(const uint8_t *data, size_t bytes)
{
	if (!fd_.isValid())
		return -EBADF;
	ssize_t n;
	do
		n = ::write(fd_.get(), data, bytes);
	while (n < 0 && errno == EINTR);
	return n < 0 ? -errno : n;
}

void V4l2OutputDevice::close()
{
	fd_.reset();
}

} // namespace depthkey
