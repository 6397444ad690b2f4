// What the SSE2, SSSE3 and AVX2 rows of the board warp
// (board_warp_rows_sse2.cpp, board_warp_rows_ssse3.cpp,
// board_warp_rows_avx2.cpp) share, in SSE2 alone: the row's pointers, a
// group of four output pixels' source taps, the groups that need no
// arithmetic, and the pshufb masks of the SSSE3 plan (the AVX2 row uses them
// in each 128-bit half). Included only where __SSE2__ is defined.
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

// Four RGB pixels as 16 bytes, the first 12 theirs: one load where the row
// has 16 bytes from p (whole = true), else no byte beyond read.
inline __m128i loadRgbBytes(const Rgb8 *p, bool whole)
{
	if (whole)
		return _mm_loadu_si128(reinterpret_cast<const __m128i *>(p));
	uint32_t last;
	std::memcpy(&last, reinterpret_cast<const uint8_t *>(p) + 8, 4);
	return _mm_unpacklo_epi64(_mm_loadl_epi64(reinterpret_cast<const __m128i *>(p)), _mm_cvtsi32_si128(int(last)));
}

// The first 12 bytes of rgb stored (four RGB pixels), no byte beyond written.
inline void storeRgbBytes(Rgb8 *p, __m128i rgb)
{
	uint8_t *b = reinterpret_cast<uint8_t *>(p);
	_mm_storel_epi64(reinterpret_cast<__m128i *>(b), rgb);
	const uint32_t last = uint32_t(_mm_cvtsi128_si32(_mm_srli_si128(rgb, 8)));
	std::memcpy(b + 8, &last, 4);
}

// The pshufb masks of the SSSE3 plan (board_warp_rows_ssse3.cpp), per 128
// bits; Z is a zero byte.
namespace shuffle {
constexpr char Z = char(0x80);
// 8-byte tap pairs [a left, a right, b left, b right] -> 16-bit [a, b].
alignas(16) inline constexpr char kLeftTaps[16] = { 0, Z, 1, Z, 2, Z, 3, Z, 8, Z, 9, Z, 10, Z, 11, Z };
alignas(16) inline constexpr char kRightTaps[16] = { 4, Z, 5, Z, 6, Z, 7, Z, 12, Z, 13, Z, 14, Z, 15, Z };
// 16-bit [fx0 fy0 fx1 fy1 fx2 fy2 fx3 fy3] -> a pair's fractions, four lanes each.
alignas(16) inline constexpr char kFx01[16] = { 0, 1, 0, 1, 0, 1, 0, 1, 4, 5, 4, 5, 4, 5, 4, 5 };
alignas(16) inline constexpr char kFy01[16] = { 2, 3, 2, 3, 2, 3, 2, 3, 6, 7, 6, 7, 6, 7, 6, 7 };
alignas(16) inline constexpr char kFx23[16] = { 8, 9, 8, 9, 8, 9, 8, 9, 12, 13, 12, 13, 12, 13, 12, 13 };
alignas(16) inline constexpr char kFy23[16] = { 10, 11, 10, 11, 10, 11, 10, 11, 14, 15, 14, 15, 14, 15, 14, 15 };
// Four RGBA samples -> their alphas, 16-bit lanes 0-3.
alignas(16) inline constexpr char kAlphaWords[16] = { 3, Z, 7, Z, 11, Z, 15, Z, Z, Z, Z, Z, Z, Z, Z, Z };
// 16-bit lanes 0-3 -> a pair's, four lanes each.
alignas(16) inline constexpr char kLanes01[16] = { 0, 1, 0, 1, 0, 1, 0, 1, 2, 3, 2, 3, 2, 3, 2, 3 };
alignas(16) inline constexpr char kLanes23[16] = { 4, 5, 4, 5, 4, 5, 4, 5, 6, 7, 6, 7, 6, 7, 6, 7 };
// Four RGB pixels (12 bytes) -> 16-bit RGBx of a pair.
alignas(16) inline constexpr char kRgb01[16] = { 0, Z, 1, Z, 2, Z, Z, Z, 3, Z, 4, Z, 5, Z, Z, Z };
alignas(16) inline constexpr char kRgb23[16] = { 6, Z, 7, Z, 8, Z, Z, Z, 9, Z, 10, Z, 11, Z, Z, Z };
// Four RGBx pixels -> 12 RGB bytes.
alignas(16) inline constexpr char kPackRgb[16] = { 0, 1, 2, 4, 5, 6, 8, 9, 10, 12, 13, 14, Z, Z, Z, Z };
} // namespace shuffle

inline __m128i loadMask(const char (&mask)[16])
{
	return _mm_load_si128(reinterpret_cast<const __m128i *>(mask));
}

} // namespace depthkey::warp_x86
