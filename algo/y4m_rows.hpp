// Row kernels and the frame-rate rational for YUV4MPEG2 output
// (depthkey-shmcat): full-range BT.601 RGB(A) -> Y'CbCr 4:4:4, the 2x2 chroma
// average for 4:2:0, and a measured rate written as a y4m "F<num>:<den>".
// Pure and integer only; nothing allocates.
#pragma once

#include <cstdint>

namespace depthkey {

// One row of RGB24 (bpp 3) or RGBA32 (bpp 4) to full-resolution planes;
// a may be null (alpha is then not written).
void rgbToYuv444Row_C(const uint8_t *src, int width, int bpp, uint8_t *y, uint8_t *u,
		      uint8_t *v, uint8_t *a);

// One output row of 4:2:0 chroma from two full-resolution chroma rows:
// (width + 1) / 2 values, each the rounded mean of a 2x2 block. An odd last
// column is averaged with itself; for an odd last row pass row0 twice.
void subsampleChromaRow_C(const uint8_t *row0, const uint8_t *row1, int width, uint8_t *dst);

struct FrameRate {
	uint32_t num = 25;
	uint32_t den = 1;
};

// Lowest and highest rates written; a measurement outside is not believed.
constexpr double kMinFrameRate = 0.5;
constexpr double kMaxFrameRate = 1000.0;

// The y4m rational for a measured rate (frames per second, within
// kMinFrameRate..kMaxFrameRate): the NTSC rates (24, 30, 60 x 1000/1001)
// when within 0.1%, a whole number when within 0.5%, else the rate to
// 1/1000 fps, reduced.
FrameRate y4mFrameRate(double fps);

} // namespace depthkey
