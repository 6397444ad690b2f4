// What the SSE2 and SSSE3 rows of the board warp (board_warp_rows_sse2.cpp,
// board_warp_rows_ssse3.cpp) share, in SSE2 alone: the row's pointers, a
// group of four output pixels' source taps, and the groups that need no
// arithmetic. Included only where __SSE2__ is defined.
#pragma once

#include "algo/board_warp_rows.hpp"

#include <emmintrin.h>

#include <cstring>

namespace depthkey::warp_x86 {

// Some of the four pixels from index on unseen (they run the C pixel).
inline bool anyUnseen(const int32_t *index)
{
	const __m128i k = _mm_loadu_si128(reinterpret_cast<const __m128i *>(index));
	return _mm_movemask_epi8(_mm_cmpeq_epi32(k, _mm_set1_epi32(kOutsideView))) != 0;
}

// Two pixels' 8-byte tap pairs in one register, [a left, a right, b left,
// b right]: a load and a movhps.
inline __m128i loadTaps(const Rgba8 *a, const Rgba8 *b)
{
	const __m128i lo = _mm_loadl_epi64(reinterpret_cast<const __m128i *>(a));
	return _mm_castps_si128(_mm_loadh_pi(_mm_castsi128_ps(lo), reinterpret_cast<const __m64 *>(b)));
}

// The taps of four seen pixels from index on, two pixels a register.
struct GroupTaps {
	__m128i top01, top23, bottom01, bottom23;
};

inline GroupTaps loadGroupTaps(const Rgba8 *source, ptrdiff_t stride, const int32_t *index)
{
	const Rgba8 *s0 = source + index[0], *s1 = source + index[1], *s2 = source + index[2], *s3 = source + index[3];
	return { loadTaps(s0, s1), loadTaps(s2, s3), loadTaps(s0 + stride, s1 + stride), loadTaps(s2 + stride, s3 + stride) };
}

// Whether any of the group's taps has alpha (else nobody is there).
inline bool anyAlpha(const GroupTaps &t)
{
	const __m128i any = _mm_or_si128(_mm_or_si128(t.top01, t.bottom01), _mm_or_si128(t.top23, t.bottom23));
	const __m128i none = _mm_cmpeq_epi32(_mm_and_si128(any, _mm_set1_epi32(int(0xFF000000u))), _mm_setzero_si128());
	return _mm_movemask_epi8(none) != 0xFFFF;
}

// Four RGBA samples, those with alpha 0 all 0 (the C row's transparent pixel).
inline __m128i dropTransparent(__m128i samples)
{
	const __m128i alpha = _mm_and_si128(samples, _mm_set1_epi32(int(0xFF000000u)));
	return _mm_andnot_si128(_mm_cmpeq_epi32(alpha, _mm_setzero_si128()), samples);
}

// The row's pointers as locals: the rows store through byte pointers, which
// may alias the row itself.
struct RowPointers {
	explicit RowPointers(const BoardWarpRow &r)
		: index(r.index), frac(r.frac), source(r.source), stride(r.stride), board(r.board),
		  composite(r.composite), layer(r.layer), count(r.count)
	{
	}
	const int32_t *index;
	const uint16_t *frac;
	const Rgba8 *source;
	ptrdiff_t stride;
	const Rgb8 *board;
	Rgb8 *composite;
	Rgba8 *layer;
	int count;
};

// The group of four from x when it needs no arithmetic, and then true: a
// pixel of it unseen (the C pixels), or no alpha in its taps (the board,
// transparent). Else its taps in t.
inline bool groupWithoutArithmetic(const BoardWarpRow &r, const RowPointers &p, int x, int opacityQ8, GroupTaps &t)
{
	if (anyUnseen(p.index + x)) {
		for (int i = x; i < x + 4; ++i)
			boardWarpPixel_C(r, i, opacityQ8);
		return true;
	}
	t = loadGroupTaps(p.source, p.stride, p.index + x);
	if (anyAlpha(t))
		return false;
	std::memcpy(p.composite + x, p.board + x, 4 * sizeof(Rgb8));
	_mm_storeu_si128(reinterpret_cast<__m128i *>(p.layer + x), _mm_setzero_si128());
	return true;
}

} // namespace depthkey::warp_x86
