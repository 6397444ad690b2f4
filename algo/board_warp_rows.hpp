// The row kernels of the board-geometry composite (algo/board_compositor.hpp),
// a plain C reference (_C) and SSE2, SSSE3, AVX2 and NEON variants (_SSE2,
// board_warp_rows_sse2.cpp; _SSSE3, board_warp_rows_ssse3.cpp; _AVX2,
// board_warp_rows_avx2.cpp; _NEON, board_warp_rows_neon.cpp) that give the
// same bytes
// (tests/board_warp_rows_test.cpp).
//
// Each output pixel has a precomputed source: the index of the top-left of
// the 2x2 colour pixels it samples (kOutsideView = the camera does not see
// it) and the Q8 fractions fx | fy << 8. The source is the camera-geometry
// lecturer layer (RGBA, straight alpha), so that one 8-byte load fetches two
// neighbours with their alpha. Bilinear in two rounded steps, vertical then
// horizontal, each (a * (256 - f) + b * f + 128) >> 8; then the camera
// composite's blend with w = compositeWeight(opacity, alpha).
//
// The row writes every pixel of composite and layer: a pixel nobody is at
// (unseen, or its sampled alpha 0) is the board, and transparent in the
// layer with no colour either ({0, 0, 0, 0}: the SIMD rows mask the layer
// by its own alpha, and skip the arithmetic for groups of four whose taps
// all have alpha 0). So the
// compositor copies the board and clears the layer only around the rows it
// warps (each byte of the frame written once).
#pragma once

#include "algo/composite.hpp"
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

namespace warp_detail {

inline unsigned lerp8(unsigned a, unsigned b, unsigned f)
{
	return (a * (256u - f) + b * f + 128u) >> 8;
}

} // namespace warp_detail

// Output pixel x of the C reference (the SIMD rows' tails and their groups
// with an unseen pixel run it too, so all rows share one definition).
inline void boardWarpPixel_C(const BoardWarpRow &r, int x, int opacityQ8)
{
	using warp_detail::lerp8;
	const int32_t k = r.index[x];
	const Rgba8 *s = k == kOutsideView ? nullptr : r.source + k;
	if (!s || (s[0].a | s[1].a | s[r.stride].a | s[r.stride + 1].a) == 0) {
		r.composite[x] = r.board[x]; // nobody there: the board, transparent
		r.layer[x] = { 0, 0, 0, 0 };
		return;
	}
	const Rgba8 p00 = s[0], p01 = s[1], p10 = s[r.stride], p11 = s[r.stride + 1];
	const unsigned fx = r.frac[x] & 255u, fy = r.frac[x] >> 8;
	auto sample = [&](uint8_t Rgba8::*c) {
		return lerp8(lerp8(p00.*c, p10.*c, fy), lerp8(p01.*c, p11.*c, fy), fx);
	};
	const unsigned cr = sample(&Rgba8::r), cg = sample(&Rgba8::g), cb = sample(&Rgba8::b), ca = sample(&Rgba8::a);
	if (ca == 0) {
		r.composite[x] = r.board[x]; // the blend would weigh the sample 0
		r.layer[x] = { 0, 0, 0, 0 };
		return;
	}
	const unsigned w = compositeWeight(opacityQ8, uint8_t(ca)), wb = 256u - w;
	const Rgb8 b = r.board[x];
	r.composite[x] = { uint8_t((b.r * wb + cr * w + 128u) >> 8), uint8_t((b.g * wb + cg * w + 128u) >> 8),
			   uint8_t((b.b * wb + cb * w + 128u) >> 8) };
	r.layer[x] = { uint8_t(cr), uint8_t(cg), uint8_t(cb), uint8_t(ca) };
}

void boardWarpRow_C(const BoardWarpRow &row, int opacityQ8);
void boardWarpRow_SSE2(const BoardWarpRow &row, int opacityQ8);
// Only where cpuHasSsse3() (built for x86 alone: elsewhere the C row).
void boardWarpRow_SSSE3(const BoardWarpRow &row, int opacityQ8);
// Only where cpuHasAvx2() (which implies SSSE3; built for x86 alone).
void boardWarpRow_AVX2(const BoardWarpRow &row, int opacityQ8);
void boardWarpRow_NEON(const BoardWarpRow &row, int opacityQ8);

using BoardWarpRowFn = void (*)(const BoardWarpRow &row, int opacityQ8);
// The row of path on this CPU (Avx2 without AVX2: the Ssse3 path's row;
// Ssse3 without SSSE3: the SSE2 row); chosen
// once per image.
BoardWarpRowFn boardWarpRowFn(KernelPath path);
void boardWarpRow(KernelPath path, const BoardWarpRow &row, int opacityQ8);

} // namespace depthkey
