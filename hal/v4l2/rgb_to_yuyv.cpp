#include "hal/v4l2/rgb_to_yuyv.hpp"

#include "hal/v4l2/rgb_to_yuyv_coefficients.hpp"

#include <cerrno>

namespace depthkey {

namespace {

using namespace yuyv;

inline uint8_t luma(const Rgb8 &p)
{
	return static_cast<uint8_t>((kYr * p.r + kYg * p.g + kYb * p.b + kLumaBias) >> 16);
}

} // namespace

void rgbToYuyvRow_C(const Rgb8 *rgb, uint8_t *yuyv, int width)
{
	for (int x = 0; x < width; x += 2, yuyv += 4) {
		const Rgb8 &a = rgb[x];
		const Rgb8 &b = x + 1 < width ? rgb[x + 1] : a;
		int r = a.r + b.r, g = a.g + b.g, bl = a.b + b.b;
		yuyv[0] = luma(a);
		yuyv[1] = static_cast<uint8_t>((kUr * r + kUg * g + kUb * bl + kChromaBias) >> 17);
		yuyv[2] = luma(b);
		yuyv[3] = static_cast<uint8_t>((kVr * r + kVg * g + kVb * bl + kChromaBias) >> 17);
	}
}

int rgbToYuyv(const RgbImage &image, uint8_t *yuyv, size_t bytes, KernelPath path)
{
	auto row = sse2Rows(path)	      ? rgbToYuyvRow_SSE2
		   : path == KernelPath::Neon ? rgbToYuyvRow_NEON
					      : rgbToYuyvRow_C;
	const int width = image.width(), height = image.height();
	if (bytes < yuyvFrameBytes(width, height))
		return -EMSGSIZE;
	const size_t rowBytes = static_cast<size_t>(yuyvWidth(width)) * 2;
	for (int y = 0; y < height; y++)
		row(image.row(y), yuyv + rowBytes * static_cast<size_t>(y), width);
	return 0;
}

} // namespace depthkey
