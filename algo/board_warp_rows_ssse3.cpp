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

constexpr char Z = char(0x80); // pshufb: a zero byte

struct Constants {
	const __m128i zero = _mm_setzero_si128();
	const __m128i half = _mm_set1_epi16(128);
	// compositeWeight(o, a) = (p + (p >> 8)) >> 8 with p = o a + 128 < 65536:
	// exactly the high half of p * 257.
	const __m128i v257 = _mm_set1_epi16(257);
	// 8-byte tap pairs [a left, a right, b left, b right] -> 16-bit [a, b].
	const __m128i leftTaps = _mm_setr_epi8(0, Z, 1, Z, 2, Z, 3, Z, 8, Z, 9, Z, 10, Z, 11, Z);
	const __m128i rightTaps = _mm_setr_epi8(4, Z, 5, Z, 6, Z, 7, Z, 12, Z, 13, Z, 14, Z, 15, Z);
	// 16-bit [fx0 fy0 fx1 fy1 fx2 fy2 fx3 fy3] -> a pair's fractions, four lanes each.
	const __m128i fx01 = _mm_setr_epi8(0, 1, 0, 1, 0, 1, 0, 1, 4, 5, 4, 5, 4, 5, 4, 5);
	const __m128i fy01 = _mm_setr_epi8(2, 3, 2, 3, 2, 3, 2, 3, 6, 7, 6, 7, 6, 7, 6, 7);
	const __m128i fx23 = _mm_setr_epi8(8, 9, 8, 9, 8, 9, 8, 9, 12, 13, 12, 13, 12, 13, 12, 13);
	const __m128i fy23 = _mm_setr_epi8(10, 11, 10, 11, 10, 11, 10, 11, 14, 15, 14, 15, 14, 15, 14, 15);
	// Four RGBA samples -> their alphas, 16-bit lanes 0-3.
	const __m128i alphaWords = _mm_setr_epi8(3, Z, 7, Z, 11, Z, 15, Z, Z, Z, Z, Z, Z, Z, Z, Z);
	// 16-bit lanes 0-3 -> a pair's, four lanes each.
	const __m128i lanes01 = _mm_setr_epi8(0, 1, 0, 1, 0, 1, 0, 1, 2, 3, 2, 3, 2, 3, 2, 3);
	const __m128i lanes23 = _mm_setr_epi8(4, 5, 4, 5, 4, 5, 4, 5, 6, 7, 6, 7, 6, 7, 6, 7);
	// Four RGB pixels (12 bytes) -> 16-bit RGBx of a pair.
	const __m128i rgb01 = _mm_setr_epi8(0, Z, 1, Z, 2, Z, Z, Z, 3, Z, 4, Z, 5, Z, Z, Z);
	const __m128i rgb23 = _mm_setr_epi8(6, Z, 7, Z, 8, Z, Z, Z, 9, Z, 10, Z, 11, Z, Z, Z);
	// Four RGBx pixels -> 12 RGB bytes.
	const __m128i packRgb = _mm_setr_epi8(0, 1, 2, 4, 5, 6, 8, 9, 10, 12, 13, 14, Z, Z, Z, Z);
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

// Four RGB pixels as 16 bytes, the first 12 theirs: one load where the row
// has 16 bytes from p (whole = true), else no byte beyond read.
SSSE3 inline __m128i loadRgb4(const Rgb8 *p, bool whole)
{
	if (whole)
		return _mm_loadu_si128(reinterpret_cast<const __m128i *>(p));
	uint32_t last;
	std::memcpy(&last, reinterpret_cast<const uint8_t *>(p) + 8, 4);
	return _mm_unpacklo_epi64(_mm_loadl_epi64(reinterpret_cast<const __m128i *>(p)), _mm_cvtsi32_si128(int(last)));
}

// 12 RGB bytes stored, no byte beyond written.
SSSE3 inline void storeRgb4(Rgb8 *p, __m128i rgb)
{
	uint8_t *b = reinterpret_cast<uint8_t *>(p);
	_mm_storel_epi64(reinterpret_cast<__m128i *>(b), rgb);
	const uint32_t last = uint32_t(_mm_cvtsi128_si32(_mm_srli_si128(rgb, 8)));
	std::memcpy(b + 8, &last, 4);
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
		const __m128i under = loadRgb4(p.board + x, x + 6 <= p.count);
		const __m128i c01 = lerp(_mm_shuffle_epi8(under, k.rgb01), h01, _mm_shuffle_epi8(w7, k.lanes01));
		const __m128i c23 = lerp(_mm_shuffle_epi8(under, k.rgb23), h23, _mm_shuffle_epi8(w7, k.lanes23));
		storeRgb4(p.composite + x, _mm_shuffle_epi8(_mm_packus_epi16(c01, c23), k.packRgb));
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
