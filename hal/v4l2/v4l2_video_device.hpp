// A V4L2 single-planar capture device with explicit steps, in the order a
// stream uses them: open, setFormat, setFrameRate, allocateBuffers (mmap),
// queue all, streamOn, dequeue/queue per frame, streamOff, releaseBuffers,
// close. Every call returns a negative errno; nothing throws or blocks (the
// fd is non-blocking, dequeue says -EAGAIN when no buffer is ready).
#pragma once

#include "hal/unique_fd.hpp"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace depthkey {

struct V4l2Format {
	uint32_t fourcc = 0;
	int width = 0;
	int height = 0;
	uint32_t bytesPerLine = 0;
	uint32_t sizeImage = 0;
};

struct V4l2Buffer {
	unsigned index = 0;
	const uint8_t *data = nullptr;
	size_t bytesUsed = 0;
	uint64_t timestampNs = 0;   // CLOCK_MONOTONIC, 0 if the driver gives none
	uint32_t sequence = 0;
	bool error = false;         // V4L2_BUF_FLAG_ERROR: contents unreliable
};

std::string fourccName(uint32_t fourcc); // "YUYV"

class V4l2VideoDevice
{
public:
	V4l2VideoDevice() = default;
	~V4l2VideoDevice() { close(); }
	V4l2VideoDevice(const V4l2VideoDevice &) = delete;
	V4l2VideoDevice &operator=(const V4l2VideoDevice &) = delete;

	// A capture + streaming device; path may be a /dev/v4l/by-id link.
	int open(const std::string &path);
	void close();
	int fd() const { return fd_.get(); }
	const std::string &card() const { return card_; }

	std::vector<uint32_t> formats(); // what the device offers (ENUM_FMT)
	// Sets format; on success format holds what the driver chose.
	int setFormat(V4l2Format &format);
	int setFrameRate(int fps); // best effort: -ENOTTY when the driver has no S_PARM

	int allocateBuffers(unsigned count); // returns how many were mapped
	void releaseBuffers();
	int queueBuffer(unsigned index);
	int dequeueBuffer(V4l2Buffer &buffer);
	int streamOn();
	int streamOff();

private:
	int ioctlRetry(unsigned long request, void *arg);

	struct Mapping {
		void *address = nullptr;
		size_t length = 0;
	};
	UniqueFd fd_;
	bool streaming_ = false;
	std::string card_;
	std::vector<Mapping> buffers_;
};

} // namespace depthkey
