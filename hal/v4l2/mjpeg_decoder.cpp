#include "hal/v4l2/mjpeg_decoder.hpp"

#include <cerrno>
#include <turbojpeg.h>

namespace depthkey {

MjpegDecoder::~MjpegDecoder()
{
	if (handle_)
		tjDestroy(handle_);
}

int MjpegDecoder::decode(const uint8_t *jpeg, size_t bytes, int width, int height, RgbImage &out)
{
	if (!handle_ && !(handle_ = tjInitDecompress()))
		return -ENOMEM;
	int w = 0, h = 0, subsampling = 0, colourspace = 0;
	if (bytes == 0 || tjDecompressHeader3(handle_, jpeg, bytes, &w, &h, &subsampling,
					      &colourspace) < 0) {
		lastError_ = bytes ? tjGetErrorStr2(handle_) : "empty buffer";
		return -EBADMSG;
	}
	if (w != width || h != height) {
		lastError_ = "JPEG is " + std::to_string(w) + "x" + std::to_string(h);
		return -EINVAL;
	}
	out.resize(width, height);
	static_assert(sizeof(Rgb8) == 3, "RGB24 rows are decoded in place");
	// TJFLAG_STOPONWARNING: a truncated JPEG fails instead of decoding grey.
	int ret = tjDecompress2(handle_, jpeg, bytes, reinterpret_cast<unsigned char *>(out.data()),
				width, width * 3, height, TJPF_RGB,
				TJFLAG_STOPONWARNING | TJFLAG_FASTDCT);
	if (ret < 0) {
		lastError_ = tjGetErrorStr2(handle_);
		return -EBADMSG;
	}
	return 0;
}

} // namespace depthkey
