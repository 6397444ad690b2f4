// NEON row of algo/edge_kinds_rows.hpp: sixteen pixels a step (vld1q reads
// within [-1, n]), the five bytes summed in 16-bit lanes (vaddl_u8,
// vaddw_u8) and compared with 5 * 255 and 0, the masks narrowed back to
// bytes; fewer than sixteen left go through the C row. Built without NEON
// it is the C row.
#include "algo/edge_kinds_rows.hpp"

#include <array>

#if defined(__ARM_NEON)
#include <arm_neon.h>
#endif

namespace depthkey {

#if defined(__ARM_NEON)

void edgeKindsRow_NEON(const uint8_t *up, const uint8_t *m, const uint8_t *down, int n, uint8_t *kinds)
{
	const uint16x8_t full = vdupq_n_u16(5 * 255), zero = vdupq_n_u16(0);
	int x = 0;
	for (; x + 16 <= n; x += 16) {
		const uint8x16_t c = vld1q_u8(m + x), l = vld1q_u8(m + x - 1), r = vld1q_u8(m + x + 1);
		const uint8x16_t u = vld1q_u8(up + x), d = vld1q_u8(down + x);
		uint16x8_t lo = vaddl_u8(vget_low_u8(c), vget_low_u8(l));
		uint16x8_t hi = vaddl_high_u8(c, l);
		for (const uint8x16_t b : std::array{ r, u, d }) {
			lo = vaddw_u8(lo, vget_low_u8(b));
			hi = vaddw_high_u8(hi, b);
		}
		// 0xff where all five are 255, where all are 0.
		const uint8x16_t allOn = vcombine_u8(vmovn_u16(vceqq_u16(lo, full)), vmovn_u16(vceqq_u16(hi, full)));
		const uint8x16_t allOff = vcombine_u8(vmovn_u16(vceqq_u16(lo, zero)), vmovn_u16(vceqq_u16(hi, zero)));
		const uint8x16_t lecturerEdge = vandq_u8(vtstq_u8(c, c), vdupq_n_u8(1)); // 1 where m != 0
		const uint8x16_t edge = vbicq_u8(lecturerEdge, vorrq_u8(allOn, allOff));
		const uint8x16_t kind = vorrq_u8(edge, vorrq_u8(vandq_u8(allOn, vdupq_n_u8(kEdgeKindLecturerInside)),
							      vandq_u8(allOff, vdupq_n_u8(kEdgeKindBoardInside))));
		vst1q_u8(kinds + x, kind);
	}
	edgeKindsRow_C(up + x, m + x, down + x, n - x, kinds + x);
}

#else

void edgeKindsRow_NEON(const uint8_t *up, const uint8_t *m, const uint8_t *down, int n, uint8_t *kinds)
{
	edgeKindsRow_C(up, m, down, n, kinds);
}

#endif

} // namespace depthkey
