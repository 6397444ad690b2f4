// RGB24 to YUYV 4:2:2 (BT.601, limited range: what webcams send and what
// ffmpeg, browsers and OBS assume for a YUYV camera), in 16-bit fixed point,
// for the virtual webcam (hal/v4l2/v4l2_output.hpp). The inverse of
// yuv_to_rgb.hpp. rgbToYuyvRow_C is the plain C reference row,
// rgbToYuyvRow_SSE2 and rgbToYuyvRow_NEON (rgb_to_yuyv_sse2.cpp,
// rgb_to_yuyv_neon.cpp) give the same bytes for any width and alignment; the
// frame function picks one per frame (algo/kernel_path.hpp) and walks the
// rows into a buffer the caller sized once.
#pragma once

#include "algo/image.hpp"
#include "algo/kernel_path.hpp"

#include <cstddef>
#include <cstdint>

namespace depthkey {

// The output row width of a width-pixel image: YUYV needs pixel pairs, so an
// odd width gains one column (the last pixel repeated).
inline int yuyvWidth(int width) { return (width + 1) & ~1; }
inline size_t yuyvFrameBytes(int width, int height)
{
	return static_cast<size_t>(yuyvWidth(width)) * 2 * static_cast<size_t>(height);
}

// Y0 U Y1 V for each pixel pair; U and V from the pair's sum (its mean
// colour). An odd last pixel is paired with itself. Writes yuyvWidth(width) * 2 bytes.
void rgbToYuyvRow_C(const Rgb8 *rgb, uint8_t *yuyv, int width);
void rgbToYuyvRow_SSE2(const Rgb8 *rgb, uint8_t *yuyv, int width);
void rgbToYuyvRow_NEON(const Rgb8 *rgb, uint8_t *yuyv, int width);

// The whole image into yuyv (rows of yuyvWidth(width) * 2 bytes, no padding).
// -EMSGSIZE when bytes is less than yuyvFrameBytes().
int rgbToYuyv(const RgbImage &image, uint8_t *yuyv, size_t bytes, KernelPath path = bestKernelPath());

} // namespace depthkey
