#include "hal/preview/jpeg_encoder.hpp"

#include <cerrno>
#include <cstring>
#include <turbojpeg.h>

namespace depthkey {

JpegEncoder::~JpegEncoder()
{
	if (handle_)
		tjDestroy(handle_);
}

int JpegEncoder::encode(const uint8_t *pixels, int width, int height, int stride, JpegPixels format,
			int quality, std::vector<uint8_t> &out)
{
	if (!pixels || width < 1 || height < 1 || quality < 1 || quality > 100) {
		lastError_ = "bad picture or quality";
		return -EINVAL;
	}
	if (!handle_ && !(handle_ = tjInitCompress())) {
		lastError_ = tjGetErrorStr2(nullptr);
		return -EIO;
	}
	const int pixelFormat = format == JpegPixels::Bgr ? TJPF_BGR : format == JpegPixels::Rgb ? TJPF_RGB : TJPF_GRAY;
	const int subsampling = format == JpegPixels::Gray ? TJSAMP_GRAY : TJSAMP_420;
	// TurboJPEG writes into our buffer when it is big enough (TJFLAG_NOREALLOC).
	const unsigned long bound = tjBufSize(width, height, subsampling);
	if (out.size() < bound)
		out.resize(bound);
	unsigned char *dst = out.data();
	unsigned long bytes = bound;
	if (tjCompress2(handle_, pixels, width, stride, height, pixelFormat, &dst, &bytes, subsampling, quality,
			TJFLAG_NOREALLOC | TJFLAG_FASTDCT) != 0) {
		lastError_ = tjGetErrorStr2(handle_);
		return -EIO;
	}
	out.resize(bytes);
	return 0;
}

} // namespace depthkey
