// SSE2 row of algo/board_warp_rows.hpp: one pixel at a time (each has its
// own source), its two 8-byte source loads bilinearly mixed in 16-bit lanes,
// all four channels at once. The sums are at most 255 * 256 + 128 = 65408,
// so unsigned 16-bit lanes never overflow, and every step rounds as the C
// row does: the same bytes. Built without SSE2 it is the C row.
#include "algo/board_warp_rows.hpp"


#include <cstring>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace depthkey {

#if defined(__SSE2__)

void boardWarpRow_SSE2(const BoardWarpRow &r, int opacityQ8)
{
	const __m128i zero = _mm_setzero_si128(), half = _mm_set1_epi16(128), full = _mm_set1_epi16(256);
	const __m128i opacity = _mm_set1_epi16(short(opacityQ8)), v257 = _mm_set1_epi16(257);
	for (int x = 0; x < r.count; ++x) {
		uint64_t top, bottom;
		if (!loadTaps(r, x, top, bottom))
			continue;
		const int fx = r.frac[x] & 255, fy = r.frac[x] >> 8;
		// Lanes: p0 r g b a, p1 r g b a (the left and the right neighbour).
		__m128i t = _mm_unpacklo_epi8(_mm_cvtsi64_si128(int64_t(top)), zero);
		__m128i b = _mm_unpacklo_epi8(_mm_cvtsi64_si128(int64_t(bottom)), zero);
		const __m128i wy = _mm_set1_epi16(short(fy)), wy0 = _mm_sub_epi16(full, wy);
		__m128i v = _mm_add_epi16(_mm_mullo_epi16(t, wy0), _mm_mullo_epi16(b, wy));
		v = _mm_srli_epi16(_mm_add_epi16(v, half), 8);
		const __m128i wx = _mm_set1_epi16(short(fx)), wx0 = _mm_sub_epi16(full, wx);
		__m128i h = _mm_add_epi16(_mm_mullo_epi16(v, wx0), _mm_mullo_epi16(_mm_srli_si128(v, 8), wx));
		h = _mm_srli_epi16(_mm_add_epi16(h, half), 8);
		const uint32_t rgba = uint32_t(_mm_cvtsi128_si32(_mm_packus_epi16(h, zero)));
		std::memcpy(&r.layer[x], &rgba, 4);
		// The blend in the same lanes: w = compositeWeight(opacity, a) =
		// (p + (p >> 8)) >> 8 with p = o a + 128 < 65536, which is exactly
		// the high half of p * 257.
		const __m128i alpha = _mm_shufflelo_epi16(h, _MM_SHUFFLE(3, 3, 3, 3));
		const __m128i w = _mm_mulhi_epu16(_mm_add_epi16(_mm_mullo_epi16(alpha, opacity), half), v257);
		// Assembled in registers: a 3-byte memcpy into a 4-byte word went
		// through the stack as two stores and one wider load, which the CPU
		// cannot forward (perf: half of the row's time on that stall).
		const Rgb8 bp = r.board[x];
		const uint32_t b32 = uint32_t(bp.r) | uint32_t(bp.g) << 8 | uint32_t(bp.b) << 16;
		const __m128i bv = _mm_unpacklo_epi8(_mm_cvtsi32_si128(int(b32)), zero);
		__m128i out = _mm_add_epi16(_mm_mullo_epi16(bv, _mm_sub_epi16(full, w)), _mm_mullo_epi16(h, w));
		out = _mm_srli_epi16(_mm_add_epi16(out, half), 8);
		const uint32_t rgb = uint32_t(_mm_cvtsi128_si32(_mm_packus_epi16(out, zero)));
		std::memcpy(&r.composite[x], &rgb, 3);
	}
}

#else

void boardWarpRow_SSE2(const BoardWarpRow &row, int opacityQ8)
{
	boardWarpRow_C(row, opacityQ8);
}

#endif

} // namespace depthkey
