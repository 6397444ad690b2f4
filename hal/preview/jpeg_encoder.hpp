// Pictures -> JPEG with libjpeg-turbo's TurboJPEG API, for the preview page.
// One encoder per thread (a TurboJPEG handle is not shared); the output
// buffer is reused, so encoding allocates only when a picture grows.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace depthkey {

enum class JpegPixels { Bgr, Rgb, Gray };

class JpegEncoder
{
public:
	JpegEncoder() = default;
	~JpegEncoder();
	JpegEncoder(const JpegEncoder &) = delete;
	JpegEncoder &operator=(const JpegEncoder &) = delete;

	// quality 1..100; colour is 4:2:0, grey stays grey. Returns 0 or
	// -EINVAL / -EIO (lastError() then says what TurboJPEG said).
	int encode(const uint8_t *pixels, int width, int height, int stride, JpegPixels format,
		   int quality, std::vector<uint8_t> &out);
	const std::string &lastError() const { return lastError_; }

private:
	void *handle_ = nullptr; // tjhandle
	std::string lastError_;
};

} // namespace depthkey
