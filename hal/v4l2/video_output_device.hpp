// Where the virtual webcam's frames go: a V4L2 output node (v4l2loopback) in
// service, a fake in tests (a FIFO whose reader can stop reading or go away).
// Steps: open (with the format), write one whole frame per call, close. No
// call blocks: the fd is non-blocking, a full device says -EAGAIN.
#pragma once

#include "hal/unique_fd.hpp"

#include <cstddef>
#include <cstdint>
#include <string>
#include <sys/types.h>

namespace depthkey {

class VideoOutputDevice
{
public:
	virtual ~VideoOutputDevice() = default;

	// Opens path for frames of width x height YUYV (width even), each of
	// frameBytes bytes. Returns 0 or a negative errno; detail says which
	// step failed and why, for the journal.
	virtual int open(const std::string &path, int width, int height, size_t frameBytes,
			 std::string &detail) = 0;
	// Writes one frame: the bytes written, or a negative errno (-EAGAIN: the
	// device takes nothing now, the frame is dropped).
	virtual ssize_t write(const uint8_t *data, size_t bytes) = 0;
	virtual void close() = 0;
};

// The real backend: a V4L2 node with V4L2_CAP_VIDEO_OUTPUT (v4l2loopback),
// VIDIOC_S_FMT of V4L2_BUF_TYPE_VIDEO_OUTPUT to YUYV, frames by write().
class V4l2OutputDevice : public VideoOutputDevice
{
public:
	~V4l2OutputDevice() override { close(); }
	int open(const std::string &path, int width, int height, size_t frameBytes,
		 std::string &detail) override;
	ssize_t write(const uint8_t *data, size_t bytes) override;
	void close() override;

private:
	UniqueFd fd_;
};

} // namespace depthkey
