// NEON rows of algo/mask_rows.hpp: 16 bytes per instruction (vld1q/vst1q
// need no alignment), the tail in C, so the bytes are the C rows'. Built
// without NEON (not AArch64) they are the C rows.
#include "algo/mask_rows.hpp"

#if defined(__ARM_NEON)
#include <arm_neon.h>
#endif

namespace depthkey {

#if defined(__ARM_NEON)

void maskOrRow_NEON(uint8_t *acc, const uint8_t *src, int width)
{
	int x = 0;
	for (; x + 16 <= width; x += 16)
		vst1q_u8(acc + x, vorrq_u8(vld1q_u8(acc + x), vld1q_u8(src + x)));
	maskOrRow_C(acc + x, src + x, width - x);
}

void maskAndRow_NEON(uint8_t *acc, const uint8_t *src, int width)
{
	int x = 0;
	for (; x + 16 <= width; x += 16)
		vst1q_u8(acc + x, vandq_u8(vld1q_u8(acc + x), vld1q_u8(src + x)));
	maskAndRow_C(acc + x, src + x, width - x);
}

#else

void maskOrRow_NEON(uint8_t *acc, const uint8_t *src, int width) { maskOrRow_C(acc, src, width); }
void maskAndRow_NEON(uint8_t *acc, const uint8_t *src, int width) { maskAndRow_C(acc, src, width); }

#endif

} // namespace depthkey
