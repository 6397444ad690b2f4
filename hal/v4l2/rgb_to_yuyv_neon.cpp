// The NEON row of hal/v4l2/rgb_to_yuyv.hpp: the same bytes as
// rgbToYuyvRow_C for any width and alignment (vld3/vst4 need no alignment;
// the tail goes through the C row). Built without NEON (not AArch64) it is
// the C row.
//
// Sixteen pixels (eight pairs) a step, in the C row's 32-bit arithmetic:
// - vld3q_u8 de-interleaves R, G and B (no byte beyond the 48 is read);
// - luma: all three factors are positive and below 2^16 (kYg = 33039 too),
//   so unsigned 16 x 16 -> 32-bit multiply-accumulates, plus the bias, >> 16;
// - chroma: vpaddlq_u8 adds each pair's two pixels (<= 510, a signed 16-bit
//   lane), then signed 16 x 16 -> 32-bit multiply-accumulates with the
//   chroma factors (all within int16), plus the bias, >> 17;
// - vst4_u8 interleaves even lumas, U, odd lumas, V: Y0 U Y1 V per pair.
#include "hal/v4l2/rgb_to_yuyv.hpp"

#include "hal/v4l2/rgb_to_yuyv_coefficients.hpp"

#if defined(__ARM_NEON)
#include <arm_neon.h>
#endif

namespace depthkey {

#if defined(__ARM_NEON)

namespace {

using namespace yuyv;

static_assert(kYr > 0 && kYg > 0 && kYb > 0 && kYg < 65536);
static_assert(kUr >= -32768 && kUg >= -32768 && kUb <= 32767 && kVr <= 32767 && kVg >= -32768 && kVb >= -32768);

// Four pixels' luma (16-bit channel lanes) as 16-bit results (<= 235).
inline uint16x4_t luma4(uint16x4_t r, uint16x4_t g, uint16x4_t b)
{
	uint32x4_t y = vmlal_n_u16(vdupq_n_u32(uint32_t(kLumaBias)), r, uint16_t(kYr));
	y = vmlal_n_u16(y, g, uint16_t(kYg));
	y = vmlal_n_u16(y, b, uint16_t(kYb));
	return vshrn_n_u32(y, 16);
}

inline uint8x8_t luma8(uint8x8_t r, uint8x8_t g, uint8x8_t b)
{
	const uint16x8_t r16 = vmovl_u8(r), g16 = vmovl_u8(g), b16 = vmovl_u8(b);
	return vmovn_u16(vcombine_u16(luma4(vget_low_u16(r16), vget_low_u16(g16), vget_low_u16(b16)),
				      luma4(vget_high_u16(r16), vget_high_u16(g16), vget_high_u16(b16))));
}

// Four pairs' chroma from their sums (signed 16-bit lanes), >> 17.
inline int16x4_t chroma4(int16x4_t r, int16x4_t g, int16x4_t b, int cr, int cg, int cb)
{
	int32x4_t c = vmlal_n_s16(vdupq_n_s32(kChromaBias), r, int16_t(cr));
	c = vmlal_n_s16(c, g, int16_t(cg));
	c = vmlal_n_s16(c, b, int16_t(cb));
	return vmovn_s32(vshrq_n_s32(c, 17)); // 16..240: the same integer as the C row's >> 17
}

inline uint8x8_t chroma8(int16x8_t r, int16x8_t g, int16x8_t b, int cr, int cg, int cb)
{
	return vqmovun_s16(vcombine_s16(chroma4(vget_low_s16(r), vget_low_s16(g), vget_low_s16(b), cr, cg, cb),
					chroma4(vget_high_s16(r), vget_high_s16(g), vget_high_s16(b), cr, cg, cb)));
}

} // namespace

void rgbToYuyvRow_NEON(const Rgb8 *rgb, uint8_t *out, int width)
{
	int x = 0;
	for (; x + 16 <= width; x += 16) {
		const uint8x16x3_t p = vld3q_u8(&rgb[x].r);
		const uint8x16_t y = vcombine_u8(luma8(vget_low_u8(p.val[0]), vget_low_u8(p.val[1]), vget_low_u8(p.val[2])),
						 luma8(vget_high_u8(p.val[0]), vget_high_u8(p.val[1]), vget_high_u8(p.val[2])));
		const int16x8_t r = vreinterpretq_s16_u16(vpaddlq_u8(p.val[0]));
		const int16x8_t g = vreinterpretq_s16_u16(vpaddlq_u8(p.val[1]));
		const int16x8_t b = vreinterpretq_s16_u16(vpaddlq_u8(p.val[2]));
		uint8x8x4_t yuyv;
		yuyv.val[0] = vget_low_u8(vuzp1q_u8(y, y)); // even pixels' luma
		yuyv.val[1] = chroma8(r, g, b, kUr, kUg, kUb);
		yuyv.val[2] = vget_low_u8(vuzp2q_u8(y, y)); // odd pixels' luma
		yuyv.val[3] = chroma8(r, g, b, kVr, kVg, kVb);
		vst4_u8(out + 2 * x, yuyv);
	}
	rgbToYuyvRow_C(rgb + x, out + 2 * x, width - x); // x is even: pairs stay pairs
}

#else

void rgbToYuyvRow_NEON(const Rgb8 *rgb, uint8_t *out, int width) { rgbToYuyvRow_C(rgb, out, width); }

#endif

} // namespace depthkey
