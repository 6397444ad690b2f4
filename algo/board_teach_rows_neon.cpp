// NEON row of algo/board_teach_rows.hpp: eight pixels a step, the channels
// apart (vld3 of the sampled RGB, vld4 of the model's RGBA). Each channel
// is scaled by vqrdmulh: (2 (v << 7) g + 2^15) >> 16 = (v g + 128) >> 8,
// scaleQ8's rounding (v << 7 and g both fit signed 16 bits for g <= 32767),
// narrowed with saturation at 255 as scaleQ8's min; the mean steps a
// quarter in signed 16-bit lanes; the visit count adds 1 saturating. The
// sums gather in 16-bit lanes (at most 255 a step) flushed every 128 steps.
// Fewer than eight left go through the C row. Built without NEON it is the
// C row.
#include "algo/board_teach_rows.hpp"

#include "algo/board_model.hpp"
#include "algo/trimap.hpp"

#if defined(__ARM_NEON)
#include <arm_neon.h>
#endif

namespace depthkey {

#if defined(__ARM_NEON)

static_assert(BoardModel::kRateShift == 2, "the row's update step is a quarter");

void boardTeachRow_NEON(const Rgb8 *sampled, const uint8_t *mask, const int gainQ8[3], Rgba8 *model, int n,
			BoardTeachSums &sums)
{
	constexpr int kFlushSteps = 128;
	const int16x8_t gain[3] = { vdupq_n_s16(int16_t(gainQ8[0])), vdupq_n_s16(int16_t(gainQ8[1])),
				    vdupq_n_s16(int16_t(gainQ8[2])) };
	uint16x8_t predicted16[3], model16[3];
	uint32_t predicted32[3] = {}, model32[3] = {};
	auto clear = [&] {
		for (int c = 0; c < 3; ++c)
			predicted16[c] = model16[c] = vdupq_n_u16(0);
	};
	auto flush = [&] {
		for (int c = 0; c < 3; ++c) {
			predicted32[c] += vaddlvq_u16(predicted16[c]);
			model32[c] += vaddlvq_u16(model16[c]);
		}
		clear();
	};
	clear();
	int x = 0, steps = 0;
	for (; x + 8 <= n; x += 8) {
		const uint8x8x3_t s = vld3_u8(reinterpret_cast<const uint8_t *>(sampled + x));
		uint8x8x4_t m = vld4_u8(reinterpret_cast<const uint8_t *>(model + x));
		const uint8x8_t board = vceq_u8(vld1_u8(mask + x), vdup_n_u8(kTrimapBoard));
		const uint8x8_t seen = vtst_u8(m.val[3], m.val[3]);
		const uint8x8_t fresh = vbic_u8(board, seen), stepped = vand_u8(board, seen);
		for (int c = 0; c < 3; ++c) {
			const int16x8_t v = vreinterpretq_s16_u16(vshll_n_u8(s.val[c], 7));
			const uint8x8_t p = vqmovun_s16(vqrdmulhq_s16(v, gain[c]));
			const int16x8_t mean = vreinterpretq_s16_u16(vmovl_u8(m.val[c]));
			const int16x8_t d = vshrq_n_s16(
				vaddq_s16(vsubq_s16(vreinterpretq_s16_u16(vmovl_u8(p)), mean), vdupq_n_s16(2)), 2);
			const uint8x8_t next = vqmovun_s16(vaddq_s16(mean, d));
			predicted16[c] = vaddw_u8(predicted16[c], vand_u8(p, stepped));
			model16[c] = vaddw_u8(model16[c], vand_u8(m.val[c], stepped));
			m.val[c] = vbsl_u8(fresh, p, vbsl_u8(stepped, next, m.val[c]));
		}
		m.val[3] = vbsl_u8(fresh, vdup_n_u8(1), vbsl_u8(stepped, vqadd_u8(m.val[3], vdup_n_u8(1)), m.val[3]));
		vst4_u8(reinterpret_cast<uint8_t *>(model + x), m);
		if (++steps == kFlushSteps) {
			flush();
			steps = 0;
		}
	}
	flush();
	for (int c = 0; c < 3; ++c) {
		sums.predicted[c] += predicted32[c];
		sums.model[c] += model32[c];
	}
	boardTeachRow_C(sampled + x, mask + x, gainQ8, model + x, n - x, sums);
}

#else

void boardTeachRow_NEON(const Rgb8 *sampled, const uint8_t *mask, const int gainQ8[3], Rgba8 *model, int n,
			BoardTeachSums &sums)
{
	boardTeachRow_C(sampled, mask, gainQ8, model, n, sums);
}

#endif

} // namespace depthkey
