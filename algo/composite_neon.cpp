// NEON rows of algo/composite.hpp: the same bytes as the _C rows for any
// width and alignment (vld1/vld3/vst3/vst4 need no alignment; the tail goes
// through the C row). Built without NEON (not AArch64) they are the C rows.
//
// Unlike SSE2, NEON de-interleaves RGB on load (vld3q_u8: 16 pixels as one
// register per channel), so each pixel gets its own weight and no block
// needs the C row: every step is the C row's integer arithmetic in 16-bit
// lanes.
#include "algo/composite.hpp"

#if defined(__ARM_NEON)
#include <arm_neon.h>
#endif

namespace depthkey {

#if defined(__ARM_NEON)

namespace {

// compositeWeight for 8 alphas: p = o * a + 128 <= 256 * 255 + 128 = 65408
// fits a 16-bit lane, but p + (p >> 8) may not, so (p + (p >> 8)) >> 8 is
// taken as the halving add ((p + (p >> 8)) >> 1, no overflow) then >> 7:
// the same integer.
inline uint16x8_t weight8(uint8x8_t alpha, uint16_t opacityQ8)
{
	const uint16x8_t p = vmlaq_n_u16(vdupq_n_u16(128), vmovl_u8(alpha), opacityQ8);
	return vshrq_n_u16(vhaddq_u16(p, vshrq_n_u16(p, 8)), 7);
}

// (b * (256 - w) + l * w + 128) >> 8 for 8 bytes: at most 255 * 256 + 128
// = 65408, so the 16-bit lanes hold it exactly.
inline uint8x8_t blend8(uint8x8_t board, uint8x8_t lecturer, uint16x8_t w, uint16x8_t wb)
{
	uint16x8_t sum = vmlaq_u16(vdupq_n_u16(128), vmovl_u8(board), wb);
	sum = vmlaq_u16(sum, vmovl_u8(lecturer), w);
	return vshrn_n_u16(sum, 8);
}

inline uint8x16_t blend16(uint8x16_t board, uint8x16_t lecturer, uint16x8_t wLo, uint16x8_t wbLo, uint16x8_t wHi,
			  uint16x8_t wbHi)
{
	return vcombine_u8(blend8(vget_low_u8(board), vget_low_u8(lecturer), wLo, wbLo),
			   blend8(vget_high_u8(board), vget_high_u8(lecturer), wHi, wbHi));
}

} // namespace

void compositeRow_NEON(const Rgb8 *lecturer, const uint8_t *alpha, const Rgb8 *board,
		       int opacityQ8, Rgb8 *out, int width)
{
	const uint16_t o = static_cast<uint16_t>(opacityQ8);
	const uint16x8_t full = vdupq_n_u16(256);
	int x = 0;
	for (; x + 16 <= width; x += 16) {
		const uint8x16_t a = vld1q_u8(alpha + x);
		const uint16x8_t wLo = weight8(vget_low_u8(a), o), wHi = weight8(vget_high_u8(a), o);
		const uint16x8_t wbLo = vsubq_u16(full, wLo), wbHi = vsubq_u16(full, wHi);
		const uint8x16x3_t l = vld3q_u8(&lecturer[x].r), b = vld3q_u8(&board[x].r);
		uint8x16x3_t c;
		for (int k = 0; k < 3; ++k)
			c.val[k] = blend16(b.val[k], l.val[k], wLo, wbLo, wHi, wbHi);
		vst3q_u8(&out[x].r, c);
	}
	compositeRow_C(lecturer + x, alpha + x, board + x, opacityQ8, out + x, width - x);
}

void lecturerLayerRow_NEON(const Rgb8 *colour, const uint8_t *alpha, Rgba8 *out, int width)
{
	int x = 0;
	for (; x + 16 <= width; x += 16) {
		const uint8x16x3_t c = vld3q_u8(&colour[x].r);
		const uint8x16x4_t rgba = { { c.val[0], c.val[1], c.val[2], vld1q_u8(alpha + x) } };
		vst4q_u8(&out[x].r, rgba);
	}
	lecturerLayerRow_C(colour + x, alpha + x, out + x, width - x);
}

#else

void compositeRow_NEON(const Rgb8 *lecturer, const uint8_t *alpha, const Rgb8 *board,
		       int opacityQ8, Rgb8 *out, int width)
{
	compositeRow_C(lecturer, alpha, board, opacityQ8, out, width);
}

void lecturerLayerRow_NEON(const Rgb8 *colour, const uint8_t *alpha, Rgba8 *out, int width)
{
	lecturerLayerRow_C(colour, alpha, out, width);
}

#endif

} // namespace depthkey
