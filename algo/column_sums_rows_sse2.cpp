// SSE2 rows of algo/column_sums_rows.hpp, eight columns a step (unaligned
// loads within [0, n)); fewer than eight left go through the C row. Values
// are widened to 16 bits; a difference of 8-bit values (-255..255) is
// taken there and sign-extended to 32, products (below 2^16, exact in
// _mm_mullo_epi16) are widened before they are subtracted. SSE2 has no
// three-channel load: a colour channel's eight values are put in with
// _mm_setr_epi16. Built without SSE2 (not x86-64) they are the C rows.
#include "algo/column_sums_rows.hpp"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace depthkey {

#if defined(__SSE2__)

namespace {

inline __m128i load8(const uint8_t *p)
{
	return _mm_unpacklo_epi8(_mm_loadl_epi64(reinterpret_cast<const __m128i *>(p)), _mm_setzero_si128());
}

// s[0..8) += the eight 32-bit values d's 16-bit lanes sign-extend to.
inline void addSigned16(uint32_t *s, __m128i d)
{
	const __m128i sign = _mm_srai_epi16(d, 15);
	__m128i *v = reinterpret_cast<__m128i *>(s);
	_mm_storeu_si128(v, _mm_add_epi32(_mm_loadu_si128(v), _mm_unpacklo_epi16(d, sign)));
	_mm_storeu_si128(v + 1, _mm_add_epi32(_mm_loadu_si128(v + 1), _mm_unpackhi_epi16(d, sign)));
}

// s[0..8) += in - out, both eight unsigned 16-bit lanes, in 32 bits.
inline void addDifference(uint32_t *s, __m128i in, __m128i out)
{
	const __m128i zero = _mm_setzero_si128();
	__m128i *v = reinterpret_cast<__m128i *>(s);
	const __m128i lo = _mm_sub_epi32(_mm_unpacklo_epi16(in, zero), _mm_unpacklo_epi16(out, zero));
	const __m128i hi = _mm_sub_epi32(_mm_unpackhi_epi16(in, zero), _mm_unpackhi_epi16(out, zero));
	_mm_storeu_si128(v, _mm_add_epi32(_mm_loadu_si128(v), lo));
	_mm_storeu_si128(v + 1, _mm_add_epi32(_mm_loadu_si128(v + 1), hi));
}

} // namespace

void stepMomentColumnsRow_SSE2(const uint8_t *iIn, const uint8_t *pIn, const uint8_t *iOut, const uint8_t *pOut,
			       int n, const MomentSums &sums)
{
	int x = 0;
	for (; x + 8 <= n; x += 8) {
		const __m128i i = load8(iIn + x), p = load8(pIn + x), io = load8(iOut + x), po = load8(pOut + x);
		addSigned16(sums[0] + x, _mm_sub_epi16(i, io));
		addSigned16(sums[1] + x, _mm_sub_epi16(p, po));
		addDifference(sums[2] + x, _mm_mullo_epi16(i, i), _mm_mullo_epi16(io, io));
		addDifference(sums[3] + x, _mm_mullo_epi16(i, p), _mm_mullo_epi16(io, po));
	}
	stepMomentColumnsRow_C(iIn + x, pIn + x, iOut + x, pOut + x, n - x,
			       { sums[0] + x, sums[1] + x, sums[2] + x, sums[3] + x });
}

void stepPairColumnsRow_SSE2(const int32_t *aIn, const int32_t *bIn, const int32_t *aOut, const int32_t *bOut, int n,
			     const PairSums &sums)
{
	auto load = [](const void *p) { return _mm_loadu_si128(static_cast<const __m128i *>(p)); };
	int x = 0;
	for (; x + 4 <= n; x += 4) {
		__m128i *a = reinterpret_cast<__m128i *>(sums[0] + x), *b = reinterpret_cast<__m128i *>(sums[1] + x);
		_mm_storeu_si128(a, _mm_add_epi32(load(a), _mm_sub_epi32(load(aIn + x), load(aOut + x))));
		_mm_storeu_si128(b, _mm_add_epi32(load(b), _mm_sub_epi32(load(bIn + x), load(bOut + x))));
	}
	stepPairColumnsRow_C(aIn + x, bIn + x, aOut + x, bOut + x, n - x, { sums[0] + x, sums[1] + x });
}

void stepSideColumnsRow_SSE2(const uint8_t *kIn, const Rgb8 *cIn, const uint8_t *kOut, const Rgb8 *cOut, int n,
			     SideKinds kinds, const SideSums &sums)
{
	const __m128i lecturer = _mm_set1_epi16(kinds.lecturer), board = _mm_set1_epi16(kinds.board);
	const __m128i one = _mm_set1_epi16(1);
	int x = 0;
	for (; x + 8 <= n; x += 8) {
		const __m128i kI = load8(kIn + x), kO = load8(kOut + x);
		// 0xffff where the pixel is of that side.
		const __m128i lI = _mm_cmpeq_epi16(kI, lecturer), lO = _mm_cmpeq_epi16(kO, lecturer);
		const __m128i bI = _mm_cmpeq_epi16(kI, board), bO = _mm_cmpeq_epi16(kO, board);
		const Rgb8 *ci = cIn + x, *co = cOut + x;
		const __m128i in[3] = {
			_mm_setr_epi16(ci[0].r, ci[1].r, ci[2].r, ci[3].r, ci[4].r, ci[5].r, ci[6].r, ci[7].r),
			_mm_setr_epi16(ci[0].g, ci[1].g, ci[2].g, ci[3].g, ci[4].g, ci[5].g, ci[6].g, ci[7].g),
			_mm_setr_epi16(ci[0].b, ci[1].b, ci[2].b, ci[3].b, ci[4].b, ci[5].b, ci[6].b, ci[7].b),
		};
		const __m128i out[3] = {
			_mm_setr_epi16(co[0].r, co[1].r, co[2].r, co[3].r, co[4].r, co[5].r, co[6].r, co[7].r),
			_mm_setr_epi16(co[0].g, co[1].g, co[2].g, co[3].g, co[4].g, co[5].g, co[6].g, co[7].g),
			_mm_setr_epi16(co[0].b, co[1].b, co[2].b, co[3].b, co[4].b, co[5].b, co[6].b, co[7].b),
		};
		for (int c = 0; c < 3; ++c) {
			addSigned16(sums[size_t(c)] + x, _mm_sub_epi16(_mm_and_si128(in[c], lI), _mm_and_si128(out[c], lO)));
			addSigned16(sums[size_t(4 + c)] + x,
				    _mm_sub_epi16(_mm_and_si128(in[c], bI), _mm_and_si128(out[c], bO)));
		}
		addSigned16(sums[3] + x, _mm_sub_epi16(_mm_and_si128(lI, one), _mm_and_si128(lO, one)));
		addSigned16(sums[7] + x, _mm_sub_epi16(_mm_and_si128(bI, one), _mm_and_si128(bO, one)));
	}
	SideSums rest;
	for (size_t k = 0; k < rest.size(); ++k)
		rest[k] = sums[k] + x;
	stepSideColumnsRow_C(kIn + x, cIn + x, kOut + x, cOut + x, n - x, kinds, rest);
}

#else

void stepMomentColumnsRow_SSE2(const uint8_t *iIn, const uint8_t *pIn, const uint8_t *iOut, const uint8_t *pOut,
			       int n, const MomentSums &sums)
{
	stepMomentColumnsRow_C(iIn, pIn, iOut, pOut, n, sums);
}

void stepPairColumnsRow_SSE2(const int32_t *aIn, const int32_t *bIn, const int32_t *aOut, const int32_t *bOut, int n,
			     const PairSums &sums)
{
	stepPairColumnsRow_C(aIn, bIn, aOut, bOut, n, sums);
}

void stepSideColumnsRow_SSE2(const uint8_t *kIn, const Rgb8 *cIn, const uint8_t *kOut, const Rgb8 *cOut, int n,
			     SideKinds kinds, const SideSums &sums)
{
	stepSideColumnsRow_C(kIn, cIn, kOut, cOut, n, kinds, sums);
}

#endif

} // namespace depthkey
