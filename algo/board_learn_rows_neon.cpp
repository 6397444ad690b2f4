// NEON rows of algo/board_learn_rows.hpp, built only for NEON
// (boardLearnRows() gives the C rows elsewhere). The learn row is the teach
// row's NEON row at unit gain: its vqrdmulh of v << 7 by 256 is
// (v 2^16 + 2^15) >> 16 = v exactly, three instructions a channel on eight
// pixels, not worth a second copy of its step. The OR and select rows are
// sixteen bytes a step, what is left of a row through the C rows.
#if defined(__ARM_NEON)

#include "algo/board_learn_rows.hpp"

#include "algo/trimap.hpp"

#include <arm_neon.h>

namespace depthkey {

void boardLearnRow_NEON(const Rgb8 *colour, const uint8_t *trimap, Rgba8 *model, int n, BoardTeachSums &sums)
{
	static constexpr int kUnitGain[3] = { 256, 256, 256 };
	boardTeachRow_NEON(colour, trimap, kUnitGain, model, n, sums);
}

void boardAlphaOrRow_NEON(const uint8_t *a, const uint8_t *b, const uint8_t *c, uint8_t *out, int n)
{
	int x = 0;
	for (; x + 16 <= n; x += 16)
		vst1q_u8(out + x, vorrq_u8(vorrq_u8(vld1q_u8(a + x), vld1q_u8(b + x)), vld1q_u8(c + x)));
	boardAlphaOrRow_C(a + x, b + x, c + x, out + x, n - x);
}

void boardDecidedSelectRow_NEON(const uint8_t *near, const uint8_t *trimap, int margin, uint8_t *select, int n)
{
	static_assert(kTrimapBoard == 0 && kTrimapLecturer == 0xff, "select bytes are the compare masks");
	int x = 0;
	for (; x + 16 <= n; x += 16) {
		const uint8x16_t any =
			vorrq_u8(vorrq_u8(vld1q_u8(near + x - margin), vld1q_u8(near + x)), vld1q_u8(near + x + margin));
		const uint8x16_t t = vld1q_u8(trimap + x);
		// Not learned: board or lecturer in the trimap, or a lecturer pixel near.
		const uint8x16_t kept = vorrq_u8(vorrq_u8(vceqzq_u8(t), vceqq_u8(t, vdupq_n_u8(kTrimapLecturer))),
						 vtstq_u8(any, any));
		vst1q_u8(select + x, kept);
	}
	boardDecidedSelectRow_C(near + x, trimap + x, margin, select + x, n - x);
}

} // namespace depthkey

#endif
