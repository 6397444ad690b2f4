#include "hal/v4l2/v4l2_video_device.hpp"

#include "hal/v4l2/query_capabilities_error.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <linux/videodev2.h>
#include <sys/ioctl.h>
#include <sys/mman.h>
#include <unistd.h>

namespace depthkey {

std::string fourccName(uint32_t f)
{
	char s[5] = { static_cast<char>(f & 0xff), static_cast<char>((f >> 8) & 0xff),
		      static_cast<char>((f >> 16) & 0xff), static_cast<char>((f >> 24) & 0xff), 0 };
	return s;
}

int V4l2VideoDevice::ioctlRetry(unsigned long request, void *arg)
{
	int ret;
	do
		ret = ::ioctl(fd_.get(), request, arg);
	while (ret < 0 && errno == EINTR);
	return ret < 0 ? -errno : ret;
}

int V4l2VideoDevice::open(const std::string &path)
{
	close();
	fd_.reset(::open(path.c_str(), O_RDWR | O_NONBLOCK | O_CLOEXEC));
	if (!fd_.isValid())
		return -errno;
	v4l2_capability cap = {};
	int ret = queryCapabilitiesError(ioctlRetry(VIDIOC_QUERYCAP, &cap));
	uint32_t caps = cap.capabilities & V4L2_CAP_DEVICE_CAPS ? cap.device_caps : cap.capabilities;
	if (ret == 0 && (!(caps & V4L2_CAP_VIDEO_CAPTURE) || !(caps & V4L2_CAP_STREAMING)))
		ret = -ENODEV; // a metadata node, an output, or multi-planar only
	if (ret < 0) {
		close();
		return ret;
	}
	card_.assign(reinterpret_cast<const char *>(cap.card),
		     strnlen(reinterpret_cast<const char *>(cap.card), sizeof(cap.card)));
	return 0;
}

void V4l2VideoDevice::close()
{
	if (!fd_.isValid())
		return;
	streamOff();
	releaseBuffers();
	fd_.reset();
}

std::vector<uint32_t> V4l2VideoDevice::formats()
{
	std::vector<uint32_t> list;
	for (uint32_t i = 0;; i++) {
		v4l2_fmtdesc desc = {};
		desc.index = i;
		desc.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
		if (ioctlRetry(VIDIOC_ENUM_FMT, &desc) < 0)
			break;
		list.push_back(desc.pixelformat);
	}
	return list;
}

int V4l2VideoDevice::setFormat(V4l2Format &format)
{
	v4l2_format f = {};
	f.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
	f.fmt.pix.width = static_cast<uint32_t>(format.width);
	f.fmt.pix.height = static_cast<uint32_t>(format.height);
	f.fmt.pix.pixelformat = format.fourcc;
	f.fmt.pix.field = V4L2_FIELD_NONE;
	int ret = ioctlRetry(VIDIOC_S_FMT, &f);
	if (ret < 0)
		return ret;
	format.fourcc = f.fmt.pix.pixelformat;
	format.width = static_cast<int>(f.fmt.pix.width);
	format.height = static_cast<int>(f.fmt.pix.height);
	format.bytesPerLine = f.fmt.pix.bytesperline;
	format.sizeImage = f.fmt.pix.sizeimage;
	return 0;
}

int V4l2VideoDevice::setFrameRate(int fps)
{
	v4l2_streamparm parm = {};
	parm.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
	parm.parm.capture.timeperframe = { 1, static_cast<uint32_t>(fps) };
	return ioctlRetry(VIDIOC_S_PARM, &parm);
}

int V4l2VideoDevice::allocateBuffers(unsigned count)
{
	releaseBuffers();
	v4l2_requestbuffers req = {};
	req.count = count;
	req.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
	req.memory = V4L2_MEMORY_MMAP;
	int ret = ioctlRetry(VIDIOC_REQBUFS, &req);
	if (ret < 0)
		return ret;
	if (req.count == 0)
		return -ENOMEM;
	for (unsigned i = 0; i < req.count; i++) {
		v4l2_buffer buf = {};
		buf.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
		buf.memory = V4L2_MEMORY_MMAP;
		buf.index = i;
		ret = ioctlRetry(VIDIOC_QUERYBUF, &buf);
		void *address = ret < 0 ? MAP_FAILED
					: mmap(nullptr, buf.length, PROT_READ | PROT_WRITE, MAP_SHARED,
					       fd_.get(), buf.m.offset);
		if (address == MAP_FAILED) {
			ret = ret < 0 ? ret : -errno;
			releaseBuffers();
			return ret;
		}
		buffers_.push_back({ address, buf.length });
	}
	return static_cast<int>(buffers_.size());
}

void V4l2VideoDevice::releaseBuffers()
{
	for (Mapping &m : buffers_)
		munmap(m.address, m.length);
	bool had = !buffers_.empty();
	buffers_.clear();
	if (had && fd_.isValid()) {
		v4l2_requestbuffers req = {};
		req.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
		req.memory = V4L2_MEMORY_MMAP;
		ioctlRetry(VIDIOC_REQBUFS, &req); // count 0 frees the driver's buffers
	}
}

int V4l2VideoDevice::queueBuffer(unsigned index)
{
	if (index >= buffers_.size())
		return -EINVAL;
	v4l2_buffer buf = {};
	buf.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
	buf.memory = V4L2_MEMORY_MMAP;
	buf.index = index;
	return ioctlRetry(VIDIOC_QBUF, &buf);
}

int V4l2VideoDevice::dequeueBuffer(V4l2Buffer &out)
{
	v4l2_buffer buf = {};
	buf.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
	buf.memory = V4L2_MEMORY_MMAP;
	int ret = ioctlRetry(VIDIOC_DQBUF, &buf);
	if (ret < 0)
		return ret;
	if (buf.index >= buffers_.size())
		return -EIO;
	out.index = buf.index;
	out.data = static_cast<const uint8_t *>(buffers_[buf.index].address);
	out.bytesUsed = std::min<size_t>(buf.bytesused, buffers_[buf.index].length);
	out.sequence = buf.sequence;
	out.error = buf.flags & V4L2_BUF_FLAG_ERROR;
	bool monotonic = (buf.flags & V4L2_BUF_FLAG_TIMESTAMP_MASK) ==
			 V4L2_BUF_FLAG_TIMESTAMP_MONOTONIC;
	out.timestampNs = monotonic ? static_cast<uint64_t>(buf.timestamp.tv_sec) * 1000000000u +
					      static_cast<uint64_t>(buf.timestamp.tv_usec) * 1000u
				    : 0;
	return 0;
}

int V4l2VideoDevice::streamOn()
{
	int type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
	int ret = ioctlRetry(VIDIOC_STREAMON, &type);
	streaming_ = ret == 0;
	return ret;
}

int V4l2VideoDevice::streamOff()
{
	if (!streaming_)
		return 0;
	streaming_ = false;
	int type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
	return ioctlRetry(VIDIOC_STREAMOFF, &type);
}

} // namespace depthkey
