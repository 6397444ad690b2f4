// MJPEG frames (one JPEG per buffer) -> RGB24 with libjpeg-turbo's TurboJPEG
// API. A truncated or corrupt JPEG (TurboJPEG warns and decodes partly) is
// refused, never half-shown.
#pragma once

#include "algo/image.hpp"

#include <cstddef>
#include <cstdint>
#include <string>

namespace depthkey {

class MjpegDecoder
{
public:
	MjpegDecoder() = default;
	~MjpegDecoder();
	MjpegDecoder(const MjpegDecoder &) = delete;
	MjpegDecoder &operator=(const MjpegDecoder &) = delete;

	// -EBADMSG for a corrupt JPEG, -EINVAL when it is not width x height.
	int decode(const uint8_t *jpeg, size_t bytes, int width, int height, RgbImage &out);
	const std::string &lastError() const { return lastError_; }

private:
	void *handle_ = nullptr; // tjhandle
	std::string lastError_;
};

} // namespace depthkey
