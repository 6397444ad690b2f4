// Paper Figure 1: the lecturer laid semi-transparently over the board.
//   composite = board * (1 - o*a) + lecturer * (o*a)
// with o the configured opacity and a the alpha matte (0..255). Fixed point:
// o is Q8 (256 = opaque), the blend weight w = round(o*a/255) is Q8 too.
//
// Row kernels come as a plain C reference (_C) and SSE2 and NEON variants
// (_SSE2, algo/composite_sse2.cpp; _NEON, algo/composite_neon.cpp) that give
// the same bytes for any width and any pointer alignment
// (tests/composite_test.cpp compares them bit for bit).
#pragma once

#include "algo/image.hpp"
#include "algo/kernel_path.hpp"
#include "algo/trimap.hpp"

#include <cstdint>

namespace depthkey {

// 0..1 -> 0..256, rounded. Done once per config, not per pixel.
int opacityToQ8(double opacity);

// Blend weight of one pixel, Q8 (0..256): round(o * a / 255) without a
// division: with p = o*a + 128 <= 256*255 + 128, (p + (p >> 8)) >> 8 is
// exact for 0 <= o*a < 65536.
inline unsigned compositeWeight(int opacityQ8, uint8_t alpha)
{
	unsigned p = static_cast<unsigned>(opacityQ8) * alpha + 128u;
	return (p + (p >> 8)) >> 8;
}

// out = (board * (256 - w) + lecturer * w + 128) >> 8 per channel.
// out may alias neither input.
void compositeRow_C(const Rgb8 *lecturer, const uint8_t *alpha, const Rgb8 *board,
		    int opacityQ8, Rgb8 *out, int width);
void compositeRow_SSE2(const Rgb8 *lecturer, const uint8_t *alpha, const Rgb8 *board,
		       int opacityQ8, Rgb8 *out, int width);
void compositeRow_NEON(const Rgb8 *lecturer, const uint8_t *alpha, const Rgb8 *board,
		       int opacityQ8, Rgb8 *out, int width);
void compositeRow(KernelPath path, const Rgb8 *lecturer, const uint8_t *alpha, const Rgb8 *board,
		  int opacityQ8, Rgb8 *out, int width);

// Straight (not premultiplied) alpha, as the recorder's RGBA layer expects.
void lecturerLayerRow_C(const Rgb8 *colour, const uint8_t *alpha, Rgba8 *out, int width);
void lecturerLayerRow_SSE2(const Rgb8 *colour, const uint8_t *alpha, Rgba8 *out, int width);
void lecturerLayerRow_NEON(const Rgb8 *colour, const uint8_t *alpha, Rgba8 *out, int width);
void lecturerLayerRow(KernelPath path, const Rgb8 *colour, const uint8_t *alpha, Rgba8 *out, int width);

// Whole images; outputs are resized to the colour image's size.
void composite(const RgbImage &lecturer, const Gray8Image &alpha, const RgbImage &board,
	       int opacityQ8, RgbImage &out, KernelPath path = bestKernelPath());
// The same where alpha is known to be 0 outside roi: the composite is the
// board there, so those pixels are copied (memcpy) and only the ROI is
// blended. An empty roi gives the board. A board one row high stands for
// every row (a solid colour: the pipeline keeps no image of it).
void compositeRoi(const RgbImage &lecturer, const Gray8Image &alpha, const RgbImage &board, const Roi &roi,
		  int opacityQ8, RgbImage &out, KernelPath path = bestKernelPath());

// What compositeRoi() is made of, for making it a row at a time where it
// goes (the recorder's shared memory) without a frame-sized image of its own
// (issue 15). Borrowed: valid while the frame is published.
struct CompositeInputs {
	const RgbImage *lecturer = nullptr; // the colour frame
	const Gray8Image *alpha = nullptr;  // 0 outside roi
	const RgbImage *board = nullptr;    // the colour frame's size, or one row (a solid colour)
	Roi roi;
	int opacityQ8 = 256;
	KernelPath path = KernelPath::C;
	int width() const { return lecturer->width(); }
	int height() const { return lecturer->height(); }
};
// Row y of compositeRoi(): the same bytes. out holds width() pixels.
void compositeRoiRow(const CompositeInputs &in, int y, Rgb8 *out);
void lecturerLayer(const RgbImage &colour, const Gray8Image &alpha, RgbaImage &out,
		   KernelPath path = bestKernelPath());

} // namespace depthkey
