// SSSE3 row of algo/board_warp_rows.hpp: the SSE2 row's plan (four pixels
// a step, taps gathered with 8-byte loads, two pixels per register in 16-bit
// lanes [pixel a r g b a, pixel b r g b a]) in fewer instructions, which is
// much of its time (28 instructions a warped pixel where SSE2 takes 40,
// callgrind):
// - each lerp is a + mulhrs(b - a, f << 7): pmulhrsw gives
//   (d f 128 + 2^14) >> 15 = (d f + 128) >> 8 rounded down, and the C row's
//   (a (256 - f) + b f + 128) >> 8 is a + that, exactly (a 256 drops out of
//   the shift). Three instructions where SSE2 takes six. The blend weight
//   can be 256, whose << 7 does not fit: it is shifted with saturation to
//   32767, and mulhrs(d, 32767) = d for |d| <= 255, so b, as C gives;
// - pshufb widens taps, board pixels and fractions straight into the lanes
//   they are weighted in, and packs the composite's RGB back.
// The bytes are the C row's (tests/board_warp_rows_test.cpp). Built only
// for x86 (the instructions are enabled per function, so the rest of the
// build stays SSE2); elsewhere it is the C row. Callers check the CPU
// first (boardWarpRowFn(): the SSE2 row where SSSE3 is missing).
#include "algo/board_warp_rows.hpp"

#include <cstring>

#if defined(__SSE2__) && (defined(__x86_64__) || defined(__i386__))
#define DEPTHKEY_BOARD_WARP_SSSE3 1
#include "algo/board_warp_rows_x86.hpp"

#include <tmmintrin.h>
#define SSSE3 __attribute__((target("ssse3")))
#endif

namespace depthkey {

#if defined(DEPTHKEY_BOARD_WARP_SSSE3)

namespace {

// The masks of board_warp_rows_x86.hpp, in registers.
struct Constants {
	const __m128i zero = _mm_setzero_si128();
	const __m128i half = _mm_set1_epi16(128);
	// compositeWeight(o, a) = (p + (p >> 8)) >> 8 with p = o a + 128 < 65536:
	// exactly the high half of p * 257.
	const __m128i v257 = _mm_set1_epi16(257);
	const __m128i leftTaps = warp_x86::loadMask(warp_x86::shuffle::kLeftTaps);
	const __m128i rightTaps = warp_x86::loadMask(warp_x86::shuffle::kRightTaps);
	const __m128i fx01 = warp_x86::loadMask(warp_x86::shuffle::kFx01);
	const __m128i fy01 = warp_x86::loadMask(warp_x86::shuffle::kFy01);
	const __m128i fx23 = warp_x86::loadMask(warp_x86::shuffle::kFx23);
	const __m128i fy23 = warp_x86::loadMask(warp_x86::shuffle::kFy23);
	const __m128i alphaWords = warp_x86::loadMask(warp_x86::shuffle::kAlphaWords);
	const __m128i lanes01 = warp_x86::loadMask(warp_x86::shuffle::kLanes01);
	const __m128i lanes23 = warp_x86::loadMask(warp_x86::shuffle::kLanes23);
	const __m128i rgb01 = warp_x86::loadMask(warp_x86::shuffle::kRgb01);
	const __m128i rgb23 = warp_x86::loadMask(warp_x86::shuffle::kRgb23);
	const __m128i packRgb = warp_x86::loadMask(warp_x86::shuffle::kPackRgb);
};

// The C row's lerp, f7 = f << 7 (see the top of the file).
SSSE3 inline __m128i lerp(__m128i a, __m128i b, __m128i f7)
{
	return _mm_add_epi16(a, _mm_mulhrs_epi16(_mm_sub_epi16(b, a), f7));
}

// Two pixels' bilinear samples, 16-bit [a rgba, b rgba]: vertical, then horizontal.
SSSE3 inline __m128i samplePair(const Constants &k, __m128i top, __m128i bottom, __m128i wx, __m128i wy)
{
	const __m128i left = lerp(_mm_shuffle_epi8(top, k.leftTaps), _mm_shuffle_epi8(bottom, k.leftTaps), wy);
	const __m128i right = lerp(_mm_shuffle_epi8(top, k.rightTaps), _mm_shuffle_epi8(bottom, k.rightTaps), wy);
	return lerp(left, right, wx);
}

} // namespace

SSSE3 void boardWarpRow_SSSE3(const BoardWarpRow &r, int opacityQ8)
{
	const Constants k;
	const __m128i opacity = _mm_set1_epi16(short(opacityQ8));
	const warp_x86::RowPointers p(r);
	int x = 0;
	for (; x + 4 <= p.count; x += 4) {
		warp_x86::GroupTaps t;
		if (warp_x86::groupWithoutArithmetic(r, p, x, opacityQ8, t))
			continue;
		const __m128i fr = _mm_slli_epi16(
			_mm_unpacklo_epi8(_mm_loadl_epi64(reinterpret_cast<const __m128i *>(p.frac + x)), k.zero), 7);
		const __m128i h01 = samplePair(k, t.top01, t.bottom01, _mm_shuffle_epi8(fr, k.fx01), _mm_shuffle_epi8(fr, k.fy01));
		const __m128i h23 = samplePair(k, t.top23, t.bottom23, _mm_shuffle_epi8(fr, k.fx23), _mm_shuffle_epi8(fr, k.fy23));
		// Transparent samples have no colour (their composite is the board
		// already: alpha 0 weighs the samples 0).
		const __m128i samples = _mm_packus_epi16(h01, h23);
		_mm_storeu_si128(reinterpret_cast<__m128i *>(p.layer + x), warp_x86::dropTransparent(samples));
		// The four blend weights at once, << 7 saturated (256 -> 32767).
		const __m128i oa = _mm_add_epi16(_mm_mullo_epi16(_mm_shuffle_epi8(samples, k.alphaWords), opacity), k.half);
		const __m128i w6 = _mm_slli_epi16(_mm_mulhi_epu16(oa, k.v257), 6);
		const __m128i w7 = _mm_adds_epi16(w6, w6);
		const __m128i under = warp_x86::loadRgbBytes(p.board + x, x + 6 <= p.count);
		const __m128i c01 = lerp(_mm_shuffle_epi8(under, k.rgb01), h01, _mm_shuffle_epi8(w7, k.lanes01));
		const __m128i c23 = lerp(_mm_shuffle_epi8(under, k.rgb23), h23, _mm_shuffle_epi8(w7, k.lanes23));
		warp_x86::storeRgbBytes(p.composite + x, _mm_shuffle_epi8(_mm_packus_epi16(c01, c23), k.packRgb));
	}
	for (; x < p.count; ++x)
		boardWarpPixel_C(r, x, opacityQ8);
}

#else

void boardWarpRow_SSSE3(const BoardWarpRow &row, int opacityQ8)
{
	boardWarpRow_C(row, opacityQ8);
}

#endif

} // namespace depthkey
