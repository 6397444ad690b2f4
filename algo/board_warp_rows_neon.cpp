// NEON row of algo/board_warp_rows.hpp, the SSE2 row's plan (see
// board_warp_rows_sse2.cpp) in NEON: four pixels per step, each pixel's
// taps gathered with scalar 8-byte loads (two neighbours with their alpha),
// the weighting two pixels per register in 16-bit lanes [pixel a r g b a,
// pixel b r g b a]. Every step is the C row's (a * (256 - f) + b * f + 128)
// >> 8 or compositeWeight, integers of at most 65408 that fit a 16-bit lane,
// so the bytes are the C row's. A group with nobody in it is the board,
// transparent; a group with an unseen pixel, and the last count % 4 pixels,
// run the C row's pixel. Built without NEON (not AArch64) it is the C row.
#include "algo/board_warp_rows.hpp"

#include <cstring>

#if defined(__ARM_NEON)
#include <arm_neon.h>
#endif

namespace depthkey {

#if defined(__ARM_NEON)

namespace {

// (a * 256 + (b - a) * f + 128) >> 8: the C row's lerp, the 16-bit lanes'
// wrapping in (b - a) * f cancelling in the sum (at most 65408).
inline uint16x8_t lerp16(uint16x8_t a, uint16x8_t b, uint16x8_t f)
{
	const uint16x8_t d = vmulq_u16(vsubq_u16(b, a), f);
	return vshrq_n_u16(vaddq_u16(vaddq_u16(vshlq_n_u16(a, 8), d), vdupq_n_u16(128)), 8);
}

// Two pixels' fractions spread over their four lanes each.
inline uint16x8_t spread(unsigned a, unsigned b)
{
	return vcombine_u16(vdup_n_u16(uint16_t(a)), vdup_n_u16(uint16_t(b)));
}

// Two pixels' bilinear samples, 16-bit [a rgba, b rgba]. top and bottom: the
// pixels' tap rows, 32-bit lanes [a left, a right, b left, b right].
inline uint16x8_t samplePair(uint8x16_t top, uint8x16_t bottom, uint16_t fracA, uint16_t fracB)
{
	const uint32x4_t t = vreinterpretq_u32_u8(top), b = vreinterpretq_u32_u8(bottom);
	// Lefts [a left, b left] and rights [a right, b right], widened to 16 bits.
	const uint16x8_t tl = vmovl_u8(vget_low_u8(vreinterpretq_u8_u32(vuzp1q_u32(t, t))));
	const uint16x8_t tr = vmovl_u8(vget_low_u8(vreinterpretq_u8_u32(vuzp2q_u32(t, t))));
	const uint16x8_t bl = vmovl_u8(vget_low_u8(vreinterpretq_u8_u32(vuzp1q_u32(b, b))));
	const uint16x8_t br = vmovl_u8(vget_low_u8(vreinterpretq_u8_u32(vuzp2q_u32(b, b))));
	const uint16x8_t wy = spread(fracA >> 8, fracB >> 8), wx = spread(fracA & 255u, fracB & 255u);
	return lerp16(lerp16(tl, bl, wy), lerp16(tr, br, wy), wx);
}

// The camera composite's blend of two pixels: board (16-bit RGBx) and the
// samples h, each pixel weighted by compositeWeight of its alpha (lane 3):
// p = o a + 128 fits 16 bits, (p + (p >> 8)) >> 8 as a halving add, >> 7.
inline uint16x8_t blendPair(uint16x8_t board, uint16x8_t h, uint16_t opacity)
{
	const uint16x8_t alpha = vcombine_u16(vdup_lane_u16(vget_low_u16(h), 3), vdup_lane_u16(vget_high_u16(h), 3));
	const uint16x8_t p = vmlaq_n_u16(vdupq_n_u16(128), alpha, opacity);
	const uint16x8_t w = vshrq_n_u16(vhaddq_u16(p, vshrq_n_u16(p, 8)), 7);
	return lerp16(board, h, w);
}

// Four RGB pixels (12 bytes, none beyond read) as RGBx bytes: a table
// lookup with index 0xff (out of range) for the zero x.
inline uint8x16_t loadRgb4(const Rgb8 *p)
{
	static const uint8_t spreadRgb[16] = { 0, 1, 2, 0xff, 3, 4, 5, 0xff, 6, 7, 8, 0xff, 9, 10, 11, 0xff };
	uint8_t bytes[16] = {};
	std::memcpy(bytes, p, 12);
	return vqtbl1q_u8(vld1q_u8(bytes), vld1q_u8(spreadRgb));
}

// Four RGBx pixels stored as 12 RGB bytes, none beyond written.
inline void storeRgb4(Rgb8 *p, uint8x16_t rgbx)
{
	static const uint8_t packRgb[16] = { 0, 1, 2, 4, 5, 6, 8, 9, 10, 12, 13, 14, 0xff, 0xff, 0xff, 0xff };
	uint8_t bytes[16];
	vst1q_u8(bytes, vqtbl1q_u8(rgbx, vld1q_u8(packRgb)));
	std::memcpy(p, bytes, 12);
}

inline uint8x8_t load8(const Rgba8 *p)
{
	return vld1_u8(&p->r);
}

} // namespace

void boardWarpRow_NEON(const BoardWarpRow &r, int opacityQ8)
{
	const uint16_t opacity = uint16_t(opacityQ8);
	const uint32x4_t alphaBytes = vdupq_n_u32(0xFF000000u);
	// Locals: the stores below are through byte pointers, which may alias r.
	const int32_t *index = r.index;
	const uint16_t *frac = r.frac;
	const Rgba8 *source = r.source;
	const ptrdiff_t stride = r.stride;
	const Rgb8 *board = r.board;
	Rgb8 *composite = r.composite;
	Rgba8 *layer = r.layer;
	const int n = r.count;
	int x = 0;
	for (; x + 4 <= n; x += 4) {
		if (vmaxvq_u32(vceqq_s32(vld1q_s32(index + x), vdupq_n_s32(kOutsideView)))) {
			for (int i = x; i < x + 4; ++i)
				boardWarpPixel_C(r, i, opacityQ8);
			continue;
		}
		const Rgba8 *s0 = source + index[x], *s1 = source + index[x + 1], *s2 = source + index[x + 2],
			    *s3 = source + index[x + 3];
		const uint8x16_t top01 = vcombine_u8(load8(s0), load8(s1)), top23 = vcombine_u8(load8(s2), load8(s3));
		const uint8x16_t bottom01 = vcombine_u8(load8(s0 + stride), load8(s1 + stride));
		const uint8x16_t bottom23 = vcombine_u8(load8(s2 + stride), load8(s3 + stride));
		// Any alpha in the group's taps?
		const uint8x16_t any = vorrq_u8(vorrq_u8(top01, bottom01), vorrq_u8(top23, bottom23));
		if (vmaxvq_u32(vandq_u32(vreinterpretq_u32_u8(any), alphaBytes)) == 0) {
			std::memcpy(composite + x, board + x, 4 * sizeof(Rgb8));
			vst1q_u8(&layer[x].r, vdupq_n_u8(0));
			continue;
		}
		const uint16x8_t h01 = samplePair(top01, bottom01, frac[x], frac[x + 1]);
		const uint16x8_t h23 = samplePair(top23, bottom23, frac[x + 2], frac[x + 3]);
		// Transparent samples have no colour (their composite is the board
		// already: alpha 0 weighs the samples 0).
		const uint8x16_t samples = vcombine_u8(vmovn_u16(h01), vmovn_u16(h23));
		const uint32x4_t transparent = vceqzq_u32(vandq_u32(vreinterpretq_u32_u8(samples), alphaBytes));
		vst1q_u8(&layer[x].r, vbicq_u8(samples, vreinterpretq_u8_u32(transparent)));
		const uint8x16_t under = loadRgb4(board + x);
		const uint16x8_t c01 = blendPair(vmovl_u8(vget_low_u8(under)), h01, opacity);
		const uint16x8_t c23 = blendPair(vmovl_u8(vget_high_u8(under)), h23, opacity);
		storeRgb4(composite + x, vcombine_u8(vmovn_u16(c01), vmovn_u16(c23)));
	}
	for (; x < n; ++x)
		boardWarpPixel_C(r, x, opacityQ8);
}

#else

void boardWarpRow_NEON(const BoardWarpRow &row, int opacityQ8)
{
	boardWarpRow_C(row, opacityQ8);
}

#endif

} // namespace depthkey
