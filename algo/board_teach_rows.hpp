// The board model taught its picture's prediction (BoardModel::teach,
// algo/board_model.hpp), a row at a time. It runs over every pixel of the
// frame every frame while the board is calibrated (the box's own setup), so
// at 1920x1080 it was 140 M of a frame's instructions, more than the whole
// band's decision (issue 28). A plain C reference (_C) and SSE2, SSSE3 and
// NEON rows (board_teach_rows_sse2.cpp, _ssse3.cpp, _neon.cpp) that give its
// bytes and sums exactly (tests/board_teach_rows_test.cpp).
//
// For each pixel whose mask byte is kTrimapBoard (on the display):
//   p = BoardModel::scaleQ8(sampled, gainQ8)   the predicted empty board
//   if the model has seen the pixel (a != 0): its p and model RGB are summed
//   BoardModel::update(model, p)                a quarter of the way, a + 1
// The SIMD rows need 0 <= gainQ8 <= 32767 (16-bit lanes); boardTeachRow()
// gives the C row for other gains.
#pragma once

#include "algo/image.hpp"
#include "algo/kernel_path.hpp"

#include <cstdint>

namespace depthkey {

// The sums the model's light gain is fitted on (r, g, b).
struct BoardTeachSums {
	uint64_t predicted[3] = {};
	uint64_t model[3] = {};
};

void boardTeachRow_C(const Rgb8 *sampled, const uint8_t *mask, const int gainQ8[3], Rgba8 *model, int n,
		     BoardTeachSums &sums);
void boardTeachRow_SSE2(const Rgb8 *sampled, const uint8_t *mask, const int gainQ8[3], Rgba8 *model, int n,
			BoardTeachSums &sums);
void boardTeachRow_SSSE3(const Rgb8 *sampled, const uint8_t *mask, const int gainQ8[3], Rgba8 *model, int n,
			 BoardTeachSums &sums);
void boardTeachRow_NEON(const Rgb8 *sampled, const uint8_t *mask, const int gainQ8[3], Rgba8 *model, int n,
			BoardTeachSums &sums);
using BoardTeachRowFn = void (*)(const Rgb8 *, const uint8_t *, const int *, Rgba8 *, int, BoardTeachSums &);
// The row for path and these gains (the C row where a gain is outside
// 0..32767, or the path has no row of its own on this CPU).
BoardTeachRowFn boardTeachRow(KernelPath path, const int gainQ8[3]);

} // namespace depthkey
