// NEON row of algo/max_paint_rows.hpp: 16 bytes a step with vmaxq_u8
// (vld1q/vst1q need no alignment); the last step's value is masked to the
// lanes below n, so the bytes beyond keep theirs (max with 0). Without room
// for a 16-byte step the tail goes through the C row. Built without NEON
// (not AArch64) it is the C row.
#include "algo/max_paint_rows.hpp"

#if defined(__ARM_NEON)
#include <arm_neon.h>
#endif

namespace depthkey {

#if defined(__ARM_NEON)

void maxPaintRow_NEON(uint8_t *row, int n, int room, uint8_t value)
{
	const uint8x16_t v = vdupq_n_u8(value);
	int x = 0;
	for (; x + 16 <= n; x += 16)
		vst1q_u8(row + x, vmaxq_u8(vld1q_u8(row + x), v));
	if (x == n)
		return;
	if (x + 16 > room) {
		maxPaintRow_C(row + x, n - x, room - x, value);
		return;
	}
	const uint8x16_t mask = vld1q_u8(kFirstLanesMask + 16 - (n - x));
	vst1q_u8(row + x, vmaxq_u8(vld1q_u8(row + x), vandq_u8(v, mask)));
}

#else

void maxPaintRow_NEON(uint8_t *row, int n, int room, uint8_t value) { maxPaintRow_C(row, n, room, value); }

#endif

} // namespace depthkey
