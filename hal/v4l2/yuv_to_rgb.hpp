// YUV (BT.601, limited range: what UVC webcams and vivid send by default) to
// RGB24, in 14-bit fixed point. One row function per format is the plain C
// reference every faster variant must match; the frame functions check the
// buffer size and walk the rows. No allocation once out has the frame size.
#pragma once

#include "algo/image.hpp"

#include <cstddef>
#include <cstdint>

namespace depthkey {

// Y, Cb, Cr (0..255, limited range) -> RGB, rounded and clamped.
Rgb8 yuvToRgbPixel(int y, int u, int v);

// YUYV 4:2:2: Y0 U Y1 V for each pixel pair; an odd last pixel uses its pair's chroma.
void yuyvToRgbRow(const uint8_t *yuyv, Rgb8 *rgb, int width);
// NV12 4:2:0: a Y row and the interleaved U V row shared by two Y rows.
void nv12ToRgbRow(const uint8_t *y, const uint8_t *uv, Rgb8 *rgb, int width);

// Whole frames. bytesPerLine of the Y (or YUYV) plane; bytes is what the
// driver filled. -EMSGSIZE when the buffer is too short for the frame.
int yuyvToRgb(const uint8_t *data, size_t bytes, int width, int height,
	      size_t bytesPerLine, RgbImage &out);
int nv12ToRgb(const uint8_t *data, size_t bytes, int width, int height,
	      size_t bytesPerLine, RgbImage &out);

} // namespace depthkey
