// The row kernels of the board-geometry composite (algo/board_compositor.hpp),
// a plain C reference (_C) and an SSE2 variant (_SSE2, board_warp_rows_sse2.cpp)
// that gives the same bytes (tests/board_warp_rows_test.cpp).
//
// Each output pixel has a precomputed source: the index of the top-left of
// the 2x2 colour pixels it samples (kOutsideView = the camera does not see
// it) and the Q8 fractions fx | fy << 8. The source is the camera-geometry
// lecturer layer (RGBA, straight alpha), so that one 8-byte load fetches two
// neighbours with their alpha. Bilinear in two rounded steps, vertical then
// horizontal, each (a * (256 - f) + b * f + 128) >> 8; then the camera
// composite's blend with w = compositeWeight(opacity, alpha).
#pragma once

#include "algo/image.hpp"
#include "algo/kernel_path.hpp"

#include <cstdint>
#include <cstring>

namespace depthkey {

constexpr int32_t kOutsideView = -1;

struct BoardWarpRow {
	const int32_t *index;   // per output pixel, into source
	const uint16_t *frac;   // fx | fy << 8
	const Rgba8 *source;    // colour-camera lecturer layer
	int stride;             // its width
	const Rgb8 *board;      // the board picture's row
	Rgb8 *composite;
	Rgba8 *layer;           // the board-geometry lecturer layer
	int count;
};

// Output pixel x's source taps, two neighbours with their alpha in each
// 8-byte row; false when nobody is there (not seen, or alpha 0 in all four):
// the pixel is then the board, transparent.
inline bool loadTaps(const BoardWarpRow &r, int x, uint64_t &top, uint64_t &bottom)
{
	constexpr uint64_t kAlphaBytes = 0xFF000000FF000000ull;
	const int32_t k = r.index[x];
	if (k == kOutsideView)
		return false;
	std::memcpy(&top, r.source + k, 8);
	std::memcpy(&bottom, r.source + k + r.stride, 8);
	if (((top | bottom) & kAlphaBytes) != 0)
		return true;
	r.composite[x] = r.board[x];
	r.layer[x] = { 0, 0, 0, 0 };
	return false;
}

void boardWarpRow_C(const BoardWarpRow &row, int opacityQ8);
void boardWarpRow_SSE2(const BoardWarpRow &row, int opacityQ8);
void boardWarpRow(KernelPath path, const BoardWarpRow &row, int opacityQ8);

} // namespace depthkey
