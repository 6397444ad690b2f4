// NEON row of algo/band_scan.hpp: 16 labels a compare (vld1q needs no
// alignment, and reads only within [x, end)). NEON has no movemask: the
// 16 byte results (0xff seed, 0 not) are narrowed to 4 bits each with a
// shift-right-narrow of their 16-bit pairs, giving a 64-bit mask whose
// lowest clear nibble is the first non-seed. Fewer than 16 left go through
// the C row. Built without NEON (not AArch64) it is the C row.
#include "algo/band_scan.hpp"

#if defined(__ARM_NEON)
#include <arm_neon.h>
#endif

namespace depthkey {

#if defined(__ARM_NEON)

int nextUndecidedRow_NEON(const uint8_t *labels, int x, int end)
{
	const uint8x16_t board = vdupq_n_u8(kTrimapBoard), lecturer = vdupq_n_u8(kTrimapLecturer);
	for (; x + 16 <= end; x += 16) {
		const uint8x16_t v = vld1q_u8(labels + x);
		const uint8x16_t seeds = vorrq_u8(vceqq_u8(v, board), vceqq_u8(v, lecturer));
		const uint64_t mask = vget_lane_u64(vreinterpret_u64_u8(vshrn_n_u16(vreinterpretq_u16_u8(seeds), 4)), 0);
		if (mask != ~uint64_t(0))
			return x + __builtin_ctzll(~mask) / 4;
	}
	return nextUndecidedRow_C(labels, x, end);
}

#else

int nextUndecidedRow_NEON(const uint8_t *labels, int x, int end) { return nextUndecidedRow_C(labels, x, end); }

#endif

} // namespace depthkey
