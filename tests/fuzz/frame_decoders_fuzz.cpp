// libFuzzer harness: the V4L2 frame decoders (YUYV, NV12, MJPEG, Z16 depth)
// on any buffer with any claimed geometry, as a misbehaving driver or camera
// might hand them over. Header: format, width, height, bytes-per-line pad.
#include "hal/v4l2/depth16_to_frame.hpp"
#include "hal/v4l2/mjpeg_decoder.hpp"
#include "hal/v4l2/yuv_to_rgb.hpp"

#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	using namespace depthkey;
	if (size < 4)
		return 0;
	const int format = data[0] % 4;
	const int width = 1 + data[1] % 64, height = 1 + data[2] % 64;
	const size_t pad = data[3] % 16;
	data += 4;
	size -= 4;
	static RgbImage rgb;
	static DepthFrame depth;
	static MjpegDecoder mjpeg;
	int ret = 0;
	switch (format) {
	case 0:
		ret = yuyvToRgb(data, size, width, height, size_t(width) * 2 + pad, rgb);
		break;
	case 1:
		ret = nv12ToRgb(data, size, width, height, size_t(width) + pad, rgb);
		break;
	case 2:
		ret = mjpeg.decode(data, size, width, height, rgb);
		break;
	case 3:
		ret = depth16ToFrame(data, size, width, height, size_t(width) * 2 + pad, depthScaleQ16(1.0),
				     300, 7500, depth);
		break;
	}
	if (ret == 0 && format != 3 && (rgb.width() != width || rgb.height() != height))
		std::abort();
	return 0;
}
