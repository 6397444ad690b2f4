// NEON rows of algo/evidence_terms_rows.hpp, eight pixels a step (vld3_u8
// and vld4_u8 split the channels); fewer than eight left go through the C
// row. The board model's colour times the gain is widened to 32 bits
// (vmull_n_u16) and narrowed with a rounding shift (vrshrn_n_u32: + 128,
// >> 8), the C row's (m g + 128) >> 8. Built without NEON it is the C row.
#include "algo/evidence_terms_rows.hpp"

#if defined(__ARM_NEON)
#include <arm_neon.h>
#endif

namespace depthkey {

#if defined(__ARM_NEON)

namespace {

// |c - round(m g / 256)| for eight pixels of one channel.
inline uint16x8_t channelDistance(uint8x8_t colour, uint8x8_t model, uint16_t gain)
{
	const uint16x8_t m = vmovl_u8(model);
	const uint16x8_t gained = vcombine_u16(vrshrn_n_u32(vmull_n_u16(vget_low_u16(m), gain), 8),
					       vrshrn_n_u32(vmull_n_u16(vget_high_u16(m), gain), 8));
	return vabdq_u16(vmovl_u8(colour), gained);
}

} // namespace

void boardDistanceRow_NEON(const Rgb8 *colour, const Rgba8 *model, const int gainQ8[3], int n, int16_t *distance)
{
	const uint16_t g0 = uint16_t(gainQ8[0]), g1 = uint16_t(gainQ8[1]), g2 = uint16_t(gainQ8[2]);
	int x = 0;
	for (; x + 8 <= n; x += 8) {
		const uint8x8x3_t c = vld3_u8(&colour[x].r);
		const uint8x8x4_t m = vld4_u8(&model[x].r);
		const uint16x8_t sum = vaddq_u16(vaddq_u16(channelDistance(c.val[0], m.val[0], g0),
							   channelDistance(c.val[1], m.val[1], g1)),
						 channelDistance(c.val[2], m.val[2], g2));
		// -1 (all bits) where the model has too few visits.
		const uint16x8_t unlearned = vmovl_u8(vclt_u8(m.val[3], vdup_n_u8(kEvidenceLearnedVisits)));
		const uint16x8_t out = vorrq_u16(sum, vorrq_u16(unlearned, vshlq_n_u16(unlearned, 8)));
		vst1q_s16(distance + x, vreinterpretq_s16_u16(out));
	}
	boardDistanceRow_C(colour + x, model + x, gainQ8, n - x, distance + x);
}

void colourChangeRow_NEON(const Rgb8 *colour, const Rgb8 *previous, int n, int16_t *change)
{
	int x = 0;
	for (; x + 8 <= n; x += 8) {
		const uint8x8x3_t c = vld3_u8(&colour[x].r), p = vld3_u8(&previous[x].r);
		const uint16x8_t sum =
			vaddw_u8(vabdl_u8(c.val[0], p.val[0]), vabd_u8(c.val[1], p.val[1]));
		vst1q_s16(change + x, vreinterpretq_s16_u16(vaddw_u8(sum, vabd_u8(c.val[2], p.val[2]))));
	}
	colourChangeRow_C(colour + x, previous + x, n - x, change + x);
}

void stillHoldRow_NEON(const int16_t *change, const uint8_t *evidence, int n, const StillHold &h, uint16_t *moved,
		       uint16_t *inFront, uint8_t *held)
{
	const int16x8_t still = vdupq_n_s16(int16_t(h.still));
	const uint16x8_t pivot = vdupq_n_u16(uint16_t(h.pivot)), frame = vdupq_n_u16(h.frame);
	const uint16x8_t hold = vdupq_n_u16(uint16_t(h.holdFrames));
	int x = 0;
	for (; x + 8 <= n; x += 8) {
		const uint16x8_t m = vbslq_u16(vcgeq_s16(vld1q_s16(change + x), still), frame, vld1q_u16(moved + x));
		const uint16x8_t f = vbslq_u16(vcgtq_u16(vmovl_u8(vld1_u8(evidence + x)), pivot), frame,
					       vld1q_u16(inFront + x));
		vst1q_u16(moved + x, m);
		vst1q_u16(inFront + x, f);
		const uint16x8_t h16 = vandq_u16(vcltq_u16(vsubq_u16(frame, m), hold), vcgeq_u16(vsubq_u16(frame, f), hold));
		vst1_u8(held + x, vand_u8(vmovn_u16(h16), vdup_n_u8(1)));
	}
	stillHoldRow_C(change + x, evidence + x, n - x, h, moved + x, inFront + x, held + x);
}

#else

void stillHoldRow_NEON(const int16_t *change, const uint8_t *evidence, int n, const StillHold &h, uint16_t *moved,
		       uint16_t *inFront, uint8_t *held)
{
	stillHoldRow_C(change, evidence, n, h, moved, inFront, held);
}

void boardDistanceRow_NEON(const Rgb8 *colour, const Rgba8 *model, const int gainQ8[3], int n, int16_t *distance)
{
	boardDistanceRow_C(colour, model, gainQ8, n, distance);
}

void colourChangeRow_NEON(const Rgb8 *colour, const Rgb8 *previous, int n, int16_t *change)
{
	colourChangeRow_C(colour, previous, n, change);
}

#endif

} // namespace depthkey
