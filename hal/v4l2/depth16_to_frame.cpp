#include "hal/v4l2/depth16_to_frame.hpp"

#include <cerrno>
#include <cmath>

namespace depthkey {

uint32_t depthScaleQ16(double mmPerCount)
{
	return static_cast<uint32_t>(std::lround(mmPerCount * 65536.0));
}

void depth16ToMmRow(const uint8_t *src, uint16_t *mm, int width, uint32_t scaleQ16, int minMm,
		    int maxMm)
{
	for (int x = 0; x < width; x++) {
		uint64_t raw = static_cast<uint64_t>(src[2 * x] | src[2 * x + 1] << 8);
		// raw < 2^16, scale < 2^23 (100 mm/count): the product fits 64 bits.
		uint64_t v = (raw * scaleQ16 + 0x8000) >> 16;
		bool valid = raw != 0 && v >= static_cast<uint64_t>(minMm) &&
			     v <= static_cast<uint64_t>(maxMm);
		mm[x] = valid ? static_cast<uint16_t>(v) : 0;
	}
}

int depth16ToFrame(const uint8_t *data, size_t bytes, int width, int height, size_t bytesPerLine,
		   uint32_t scaleQ16, int minMm, int maxMm, DepthFrame &out)
{
	size_t rowBytes = static_cast<size_t>(width) * 2;
	if (bytesPerLine < rowBytes || height <= 0 ||
	    bytes < bytesPerLine * static_cast<size_t>(height - 1) + rowBytes)
		return -EMSGSIZE;
	out.depthMm.resize(width, height);
	out.amplitude.resize(width, height);
	out.intensity.resize(width, height);
	for (int y = 0; y < height; y++) {
		uint16_t *mm = out.depthMm.row(y);
		depth16ToMmRow(data + bytesPerLine * static_cast<size_t>(y), mm, width, scaleQ16,
			       minMm, maxMm);
		uint16_t *amplitude = out.amplitude.row(y);
		uint16_t *intensity = out.intensity.row(y);
		for (int x = 0; x < width; x++) {
			amplitude[x] = mm[x] ? 0xFFFF : 0;
			intensity[x] = 0;
		}
	}
	return 0;
}

} // namespace depthkey
