// SSE2 row of algo/board_warp_rows.hpp: four pixels per step. Each pixel has
// its own source, so the taps are gathered with scalar 8-byte loads (two
// neighbours with their alpha each; board_warp_rows_x86.hpp), but the
// weighting is done for two pixels per register: 16-bit lanes [pixel a r g
// b a, pixel b r g b a], each pixel's own fractions and blend weight spread
// over its four lanes. Every step is the C row's (a * (256 - f) + b * f +
// 128) >> 8, an integer of at most 255 * 256 + 128 = 65408 for f <= 256, so
// it fits a 16-bit lane (lerp16 below) and the bytes are the C row's. A
// group with nobody in it is the board, transparent, without the arithmetic;
// a group with an unseen pixel, and the last count % 4 pixels, run the C
// row's pixel. Built without SSE2 it is the C row.
#include "algo/board_warp_rows.hpp"

#include <cstring>

#if defined(__SSE2__)
#include "algo/board_warp_rows_x86.hpp"
#endif

namespace depthkey {

#if defined(__SSE2__)

namespace {

struct Constants {
	const __m128i zero = _mm_setzero_si128();
	const __m128i half = _mm_set1_epi16(128);
	// compositeWeight(o, a) = (p + (p >> 8)) >> 8 with p = o a + 128 < 65536:
	// exactly the high half of p * 257.
	const __m128i v257 = _mm_set1_epi16(257);
	// Two RGB pixels in a 64-bit lane, bytes 0-2 and 3-5; as RGBx, 0-2 and 4-6.
	const __m128i firstRgb = _mm_set1_epi64x(0x0000000000FFFFFFll);
	const __m128i secondRgbx = _mm_set1_epi64x(0x00FFFFFF00000000ll);
	const __m128i secondRgb = _mm_set1_epi64x(0x0000FFFFFF000000ll);
};

// (a * (256 - f) + b * f + 128) >> 8 per 16-bit lane, as
// (a * 256 + (b - a) * f + 128) >> 8: the same integer, at most 65408, so
// the 16-bit lanes' wrapping in (b - a) * f (negative) cancels in the sum.
// One multiply, and no 256 - f.
inline __m128i lerp16(const Constants &k, __m128i a, __m128i b, __m128i f)
{
	const __m128i d = _mm_mullo_epi16(_mm_sub_epi16(b, a), f);
	return _mm_srli_epi16(_mm_add_epi16(_mm_add_epi16(_mm_slli_epi16(a, 8), d), k.half), 8);
}

// Two pixels' bilinear samples, 16-bit [a rgba, b rgba]. top and bottom: the
// pixels' 8-byte tap rows, [a left, a right, b left, b right]; fr: 16-bit
// [fx_a fx_a fy_a fy_a fx_b fx_b fy_b fy_b].
inline __m128i samplePair(const Constants &k, __m128i top, __m128i bottom, __m128i fr)
{
	const __m128i t = _mm_shuffle_epi32(top, _MM_SHUFFLE(3, 1, 2, 0)); // a left, b left, a right, b right
	const __m128i b = _mm_shuffle_epi32(bottom, _MM_SHUFFLE(3, 1, 2, 0));
	const __m128i wx = _mm_shuffle_epi32(fr, _MM_SHUFFLE(2, 2, 0, 0)), wy = _mm_shuffle_epi32(fr, _MM_SHUFFLE(3, 3, 1, 1));
	const __m128i left = lerp16(k, _mm_unpacklo_epi8(t, k.zero), _mm_unpacklo_epi8(b, k.zero), wy);
	const __m128i right = lerp16(k, _mm_unpackhi_epi8(t, k.zero), _mm_unpackhi_epi8(b, k.zero), wy);
	return lerp16(k, left, right, wx);
}

// The camera composite's blend of two pixels: board (16-bit RGBx) and the
// samples h, each pixel weighted by its own alpha (lane 3).
inline __m128i blendPair(const Constants &k, __m128i board, __m128i h, __m128i opacity)
{
	const __m128i alpha = _mm_shufflehi_epi16(_mm_shufflelo_epi16(h, _MM_SHUFFLE(3, 3, 3, 3)), _MM_SHUFFLE(3, 3, 3, 3));
	const __m128i w = _mm_mulhi_epu16(_mm_add_epi16(_mm_mullo_epi16(alpha, opacity), k.half), k.v257);
	return lerp16(k, board, h, w);
}

// Four RGB pixels (12 bytes, no byte beyond read) as RGBx bytes.
inline __m128i loadRgb4(const Constants &k, const Rgb8 *p)
{
	const uint8_t *b = reinterpret_cast<const uint8_t *>(p);
	const __m128i v = _mm_unpacklo_epi64(_mm_loadl_epi64(reinterpret_cast<const __m128i *>(b)),
					     _mm_srli_epi64(_mm_loadl_epi64(reinterpret_cast<const __m128i *>(b + 4)), 16));
	return _mm_or_si128(_mm_and_si128(v, k.firstRgb), _mm_and_si128(_mm_slli_epi64(v, 8), k.secondRgbx));
}

// Four RGBx pixels stored as 12 RGB bytes, no byte beyond written.
inline void storeRgb4(const Constants &k, Rgb8 *p, __m128i rgbx)
{
	__m128i v = _mm_or_si128(_mm_and_si128(rgbx, k.firstRgb), _mm_and_si128(_mm_srli_epi64(rgbx, 8), k.secondRgb));
	v = _mm_or_si128(_mm_move_epi64(v), _mm_slli_si128(_mm_unpackhi_epi64(v, k.zero), 6));
	uint8_t *b = reinterpret_cast<uint8_t *>(p);
	_mm_storel_epi64(reinterpret_cast<__m128i *>(b), v);
	const uint32_t last = uint32_t(_mm_cvtsi128_si32(_mm_srli_si128(v, 8)));
	std::memcpy(b + 8, &last, 4);
}

} // namespace

void boardWarpRow_SSE2(const BoardWarpRow &r, int opacityQ8)
{
	const Constants k;
	const __m128i opacity = _mm_set1_epi16(short(opacityQ8));
	const warp_x86::RowPointers p(r);
	int x = 0;
	for (; x + 4 <= p.count; x += 4) {
		warp_x86::GroupTaps t;
		if (warp_x86::groupWithoutArithmetic(r, p, x, opacityQ8, t))
			continue;
		const __m128i fr = _mm_unpacklo_epi8(_mm_loadl_epi64(reinterpret_cast<const __m128i *>(p.frac + x)), k.zero);
		const __m128i h01 = samplePair(k, t.top01, t.bottom01, _mm_unpacklo_epi16(fr, fr));
		const __m128i h23 = samplePair(k, t.top23, t.bottom23, _mm_unpackhi_epi16(fr, fr));
		// Transparent samples have no colour (their composite is the board
		// already: alpha 0 weighs the samples 0).
		_mm_storeu_si128(reinterpret_cast<__m128i *>(p.layer + x), warp_x86::dropTransparent(_mm_packus_epi16(h01, h23)));
		const __m128i under = loadRgb4(k, p.board + x);
		const __m128i c01 = blendPair(k, _mm_unpacklo_epi8(under, k.zero), h01, opacity);
		const __m128i c23 = blendPair(k, _mm_unpackhi_epi8(under, k.zero), h23, opacity);
		storeRgb4(k, p.composite + x, _mm_packus_epi16(c01, c23));
	}
	for (; x < p.count; ++x)
		boardWarpPixel_C(r, x, opacityQ8);
}

#else

void boardWarpRow_SSE2(const BoardWarpRow &row, int opacityQ8)
{
	boardWarpRow_C(row, opacityQ8);
}

#endif

} // namespace depthkey
