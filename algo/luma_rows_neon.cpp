// NEON row of algo/luma_rows.hpp, sixteen pixels a step (vld3q_u8 splits
// the channels; R + 2 G + B in 16-bit lanes, + 2 and >> 2 by a rounding
// narrowing shift, vrshrn_n_u16); fewer than sixteen left go through the C
// row. Built without NEON it is the C row.
#include "algo/luma_rows.hpp"

#if defined(__ARM_NEON)
#include <arm_neon.h>
#endif

namespace depthkey {

#if defined(__ARM_NEON)

void lumaRow_NEON(const Rgb8 *colour, int n, uint8_t *luma)
{
	int x = 0;
	for (; x + 16 <= n; x += 16) {
		const uint8x16x3_t c = vld3q_u8(&colour[x].r);
		const uint16x8_t low = vaddq_u16(vaddl_u8(vget_low_u8(c.val[0]), vget_low_u8(c.val[2])),
						 vshll_n_u8(vget_low_u8(c.val[1]), 1));
		const uint16x8_t high = vaddq_u16(vaddl_high_u8(c.val[0], c.val[2]), vshll_high_n_u8(c.val[1], 1));
		vst1q_u8(luma + x, vcombine_u8(vrshrn_n_u16(low, 2), vrshrn_n_u16(high, 2)));
	}
	lumaRow_C(colour + x, n - x, luma + x);
}

#else

void lumaRow_NEON(const Rgb8 *colour, int n, uint8_t *luma)
{
	lumaRow_C(colour, n, luma);
}

#endif

} // namespace depthkey
