// NEON rows of algo/column_sums_rows.hpp, eight columns a step (vld1/vld3
// need no alignment and read only within [0, n)); fewer than eight left go
// through the C row. A difference of 8-bit values is taken in 16 bits
// (vsubl_u8) and sign-extended to 32; products (below 2^16, exact in
// vmulq_u16) are subtracted as they widen (vsubl_u16). vld3_u8 splits eight
// colours into their channels. Built without NEON (not AArch64) they are
// the C rows.
#include "algo/column_sums_rows.hpp"

#if defined(__ARM_NEON)
#include <arm_neon.h>
#endif

namespace depthkey {

#if defined(__ARM_NEON)

namespace {

// s[0..8) += the eight 32-bit values d's lanes (differences, as signed
// 16-bit) sign-extend to.
inline void addSigned16(uint32_t *s, uint16x8_t d)
{
	const int16x8_t v = vreinterpretq_s16_u16(d);
	vst1q_u32(s, vaddq_u32(vld1q_u32(s), vreinterpretq_u32_s32(vmovl_s16(vget_low_s16(v)))));
	vst1q_u32(s + 4, vaddq_u32(vld1q_u32(s + 4), vreinterpretq_u32_s32(vmovl_high_s16(v))));
}

// s[0..8) += in - out, both eight unsigned 16-bit lanes, in 32 bits.
inline void addDifference(uint32_t *s, uint16x8_t in, uint16x8_t out)
{
	vst1q_u32(s, vaddq_u32(vld1q_u32(s), vsubl_u16(vget_low_u16(in), vget_low_u16(out))));
	vst1q_u32(s + 4, vaddq_u32(vld1q_u32(s + 4), vsubl_high_u16(in, out)));
}

} // namespace

void stepMomentColumnsRow_NEON(const uint8_t *iIn, const uint8_t *pIn, const uint8_t *iOut, const uint8_t *pOut,
			       int n, const MomentSums &sums)
{
	int x = 0;
	for (; x + 8 <= n; x += 8) {
		const uint8x8_t i8 = vld1_u8(iIn + x), p8 = vld1_u8(pIn + x), io8 = vld1_u8(iOut + x), po8 = vld1_u8(pOut + x);
		addSigned16(sums[0] + x, vsubl_u8(i8, io8));
		addSigned16(sums[1] + x, vsubl_u8(p8, po8));
		const uint16x8_t i = vmovl_u8(i8), p = vmovl_u8(p8), io = vmovl_u8(io8), po = vmovl_u8(po8);
		addDifference(sums[2] + x, vmulq_u16(i, i), vmulq_u16(io, io));
		addDifference(sums[3] + x, vmulq_u16(i, p), vmulq_u16(io, po));
	}
	stepMomentColumnsRow_C(iIn + x, pIn + x, iOut + x, pOut + x, n - x,
			       { sums[0] + x, sums[1] + x, sums[2] + x, sums[3] + x });
}

void stepPairColumnsRow_NEON(const int32_t *aIn, const int32_t *bIn, const int32_t *aOut, const int32_t *bOut, int n,
			     const PairSums &sums)
{
	auto load = [](const int32_t *p) { return vreinterpretq_u32_s32(vld1q_s32(p)); };
	int x = 0;
	for (; x + 4 <= n; x += 4) {
		vst1q_u32(sums[0] + x, vaddq_u32(vld1q_u32(sums[0] + x), vsubq_u32(load(aIn + x), load(aOut + x))));
		vst1q_u32(sums[1] + x, vaddq_u32(vld1q_u32(sums[1] + x), vsubq_u32(load(bIn + x), load(bOut + x))));
	}
	stepPairColumnsRow_C(aIn + x, bIn + x, aOut + x, bOut + x, n - x, { sums[0] + x, sums[1] + x });
}

void stepSideColumnsRow_NEON(const uint8_t *kIn, const Rgb8 *cIn, const uint8_t *kOut, const Rgb8 *cOut, int n,
			     SideKinds kinds, const SideSums &sums)
{
	static_assert(sizeof(Rgb8) == 3, "vld3 reads packed colours");
	const uint8x8_t lecturer = vdup_n_u8(kinds.lecturer), board = vdup_n_u8(kinds.board), one = vdup_n_u8(1);
	int x = 0;
	for (; x + 8 <= n; x += 8) {
		const uint8x8_t kI = vld1_u8(kIn + x), kO = vld1_u8(kOut + x);
		// 0xff where the pixel is of that side.
		const uint8x8_t lI = vceq_u8(kI, lecturer), lO = vceq_u8(kO, lecturer);
		const uint8x8_t bI = vceq_u8(kI, board), bO = vceq_u8(kO, board);
		const uint8x8x3_t in = vld3_u8(reinterpret_cast<const uint8_t *>(cIn + x));
		const uint8x8x3_t out = vld3_u8(reinterpret_cast<const uint8_t *>(cOut + x));
		for (int c = 0; c < 3; ++c) {
			addSigned16(sums[size_t(c)] + x, vsubl_u8(vand_u8(in.val[c], lI), vand_u8(out.val[c], lO)));
			addSigned16(sums[size_t(4 + c)] + x, vsubl_u8(vand_u8(in.val[c], bI), vand_u8(out.val[c], bO)));
		}
		addSigned16(sums[3] + x, vsubl_u8(vand_u8(lI, one), vand_u8(lO, one)));
		addSigned16(sums[7] + x, vsubl_u8(vand_u8(bI, one), vand_u8(bO, one)));
	}
	SideSums rest;
	for (size_t k = 0; k < rest.size(); ++k)
		rest[k] = sums[k] + x;
	stepSideColumnsRow_C(kIn + x, cIn + x, kOut + x, cOut + x, n - x, kinds, rest);
}

#else

void stepMomentColumnsRow_NEON(const uint8_t *iIn, const uint8_t *pIn, const uint8_t *iOut, const uint8_t *pOut,
			       int n, const MomentSums &sums)
{
	stepMomentColumnsRow_C(iIn, pIn, iOut, pOut, n, sums);
}

void stepPairColumnsRow_NEON(const int32_t *aIn, const int32_t *bIn, const int32_t *aOut, const int32_t *bOut, int n,
			     const PairSums &sums)
{
	stepPairColumnsRow_C(aIn, bIn, aOut, bOut, n, sums);
}

void stepSideColumnsRow_NEON(const uint8_t *kIn, const Rgb8 *cIn, const uint8_t *kOut, const Rgb8 *cOut, int n,
			     SideKinds kinds, const SideSums &sums)
{
	stepSideColumnsRow_C(kIn, cIn, kOut, cOut, n, kinds, sums);
}

#endif

} // namespace depthkey
