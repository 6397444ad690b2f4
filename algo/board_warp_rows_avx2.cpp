// AVX2 row of algo/board_warp_rows.hpp: the SSSE3 row's plan
// (board_warp_rows_ssse3.cpp: pmulhrsw lerps, pshufb widening, the same
// masks) on eight pixels a step, each 128-bit half of a register doing what
// the SSSE3 row does in one register: pixels 0-3 in the low half, 4-7 in the
// high one. The arithmetic (most of the SSSE3 row's instructions) is halved;
// the taps are still gathered with 8-byte loads, the pairs joined with
// vinserti128 (vpgatherdq was not tried: Intel's 2023 gather-data-sampling
// microcode made it several times slower).
// A group of eight with an unseen pixel runs the SSSE3 row (its groups of
// four, and the C pixel), as do the last count % 8 pixels; a group with no
// alpha in its taps is the board, transparent, without the arithmetic.
// The bytes are the C row's (tests/board_warp_rows_test.cpp). Built only
// for x86 with the instructions enabled per function (the rest of the build
// stays SSE2); elsewhere it is the C row. Callers check the CPU first
// (boardWarpRowFn(): the SSSE3 row where AVX2 is missing).
#include "algo/board_warp_rows.hpp"

#include <cstring>

#if defined(__SSE2__) && (defined(__x86_64__) || defined(__i386__))
#define DEPTHKEY_BOARD_WARP_AVX2 1
#include "algo/board_warp_rows_x86.hpp"

#include <immintrin.h>
#define AVX2 __attribute__((target("avx2")))
#endif

namespace depthkey {

#if defined(DEPTHKEY_BOARD_WARP_AVX2)

namespace {

// A 16-byte pshufb mask of board_warp_rows_x86.hpp in both halves of a
// 32-byte one (vpshufb shuffles each half alone), kept in memory: vpshufb
// takes it as an operand, and the 16 registers stay free for the pixels.
struct alignas(32) Mask32 {
	char bytes[32];
};

constexpr Mask32 twice(const char (&mask)[16])
{
	Mask32 m{};
	for (int i = 0; i < 32; ++i)
		m.bytes[i] = mask[i % 16];
	return m;
}

template <const char (&Mask)[16]>
inline constexpr Mask32 kBoth = twice(Mask);

template <const char (&Mask)[16]>
AVX2 inline __m256i shuffle(__m256i v)
{
	return _mm256_shuffle_epi8(v, _mm256_load_si256(reinterpret_cast<const __m256i *>(kBoth<Mask>.bytes)));
}

// The C row's lerp, f7 = f << 7 (board_warp_rows_ssse3.cpp says why).
AVX2 inline __m256i lerp(__m256i a, __m256i b, __m256i f7)
{
	return _mm256_add_epi16(a, _mm256_mulhrs_epi16(_mm256_sub_epi16(b, a), f7));
}

// Four pixels' bilinear samples, 16-bit [a rgba, b rgba] in each half:
// vertical, then horizontal.
AVX2 inline __m256i sampleTwoPairs(__m256i top, __m256i bottom, __m256i wx, __m256i wy)
{
	using namespace warp_x86::shuffle;
	const __m256i left = lerp(shuffle<kLeftTaps>(top), shuffle<kLeftTaps>(bottom), wy);
	const __m256i right = lerp(shuffle<kRightTaps>(top), shuffle<kRightTaps>(bottom), wy);
	return lerp(left, right, wx);
}

AVX2 inline __m256i halves(__m128i low, __m128i high)
{
	return _mm256_inserti128_si256(_mm256_castsi128_si256(low), high, 1);
}

// The row from pixel x on, n pixels.
BoardWarpRow part(const BoardWarpRow &r, int x, int n)
{
	return { r.index + x, r.frac + x, r.source, r.stride, r.board + x, r.composite + x, r.layer + x, n };
}

} // namespace

AVX2 void boardWarpRow_AVX2(const BoardWarpRow &r, int opacityQ8)
{
	using namespace warp_x86::shuffle;
	const __m256i opacity = _mm256_set1_epi16(short(opacityQ8)), zero = _mm256_setzero_si256();
	const __m256i half = _mm256_set1_epi16(128), v257 = _mm256_set1_epi16(257); // as in the SSSE3 row
	const __m256i alphaBytes = _mm256_set1_epi32(int(0xFF000000u)), unseen = _mm256_set1_epi32(kOutsideView);
	// Four RGB pixels in each half's first 12 bytes -> 24 bytes in a row.
	const __m256i packHalves = _mm256_setr_epi32(0, 1, 2, 4, 5, 6, 7, 7);
	const warp_x86::RowPointers p(r);
	int x = 0;
	for (; x + 8 <= p.count; x += 8) {
		const __m256i k = _mm256_loadu_si256(reinterpret_cast<const __m256i *>(p.index + x));
		const __m256i unseenHere = _mm256_cmpeq_epi32(k, unseen);
		if (!_mm256_testz_si256(unseenHere, unseenHere)) {
			boardWarpRow_SSSE3(part(r, x, 8), opacityQ8);
			continue;
		}
		const warp_x86::GroupTaps lo = warp_x86::loadGroupTaps(p.source, p.stride, p.index + x);
		const warp_x86::GroupTaps hi = warp_x86::loadGroupTaps(p.source, p.stride, p.index + x + 4);
		// Halves [pixels 0 1 | 4 5] and [2 3 | 6 7].
		const __m256i top0145 = halves(lo.top01, hi.top01), top2367 = halves(lo.top23, hi.top23);
		const __m256i bottom0145 = halves(lo.bottom01, hi.bottom01), bottom2367 = halves(lo.bottom23, hi.bottom23);
		const __m256i any = _mm256_or_si256(_mm256_or_si256(top0145, top2367), _mm256_or_si256(bottom0145, bottom2367));
		if (_mm256_testz_si256(any, alphaBytes)) {
			std::memcpy(p.composite + x, p.board + x, 8 * sizeof(Rgb8)); // nobody there
			_mm256_storeu_si256(reinterpret_cast<__m256i *>(p.layer + x), zero);
			continue;
		}
		// 16-bit [fx fy] of pixels 0-3 in the low half, 4-7 in the high one.
		const __m256i fr = _mm256_slli_epi16(
			_mm256_cvtepu8_epi16(_mm_loadu_si128(reinterpret_cast<const __m128i *>(p.frac + x))), 7);
		const __m256i h0145 = sampleTwoPairs(top0145, bottom0145, shuffle<kFx01>(fr), shuffle<kFy01>(fr));
		const __m256i h2367 = sampleTwoPairs(top2367, bottom2367, shuffle<kFx23>(fr), shuffle<kFy23>(fr));
		// Pixels 0-7 in order; transparent samples have no colour.
		const __m256i samples = _mm256_packus_epi16(h0145, h2367);
		const __m256i alpha = _mm256_and_si256(samples, alphaBytes);
		_mm256_storeu_si256(reinterpret_cast<__m256i *>(p.layer + x),
				    _mm256_andnot_si256(_mm256_cmpeq_epi32(alpha, zero), samples));
		// The eight blend weights, << 7 saturated (256 -> 32767).
		const __m256i oa = _mm256_add_epi16(_mm256_mullo_epi16(shuffle<kAlphaWords>(samples), opacity), half);
		const __m256i w6 = _mm256_slli_epi16(_mm256_mulhi_epu16(oa, v257), 6);
		const __m256i w7 = _mm256_adds_epi16(w6, w6);
		const __m256i under = halves(warp_x86::loadRgbBytes(p.board + x, true),
					     warp_x86::loadRgbBytes(p.board + x + 4, x + 10 <= p.count));
		const __m256i c0145 = lerp(shuffle<kRgb01>(under), h0145, shuffle<kLanes01>(w7));
		const __m256i c2367 = lerp(shuffle<kRgb23>(under), h2367, shuffle<kLanes23>(w7));
		const __m256i rgb = _mm256_permutevar8x32_epi32(shuffle<kPackRgb>(_mm256_packus_epi16(c0145, c2367)), packHalves);
		_mm_storeu_si128(reinterpret_cast<__m128i *>(p.composite + x), _mm256_castsi256_si128(rgb));
		_mm_storel_epi64(reinterpret_cast<__m128i *>(reinterpret_cast<uint8_t *>(p.composite + x) + 16),
				 _mm256_extracti128_si256(rgb, 1));
	}
	if (x < p.count)
		boardWarpRow_SSSE3(part(r, x, p.count - x), opacityQ8);
}

#else

void boardWarpRow_AVX2(const BoardWarpRow &row, int opacityQ8)
{
	boardWarpRow_C(row, opacityQ8);
}

#endif

} // namespace depthkey
