// SSSE3 row of algo/board_teach_rows.hpp: the SSE2 row's four pixels a step
// in fewer instructions. pshufb spreads the sampled RGB to RGBA (alpha 0) in
// one instruction, and pmulhrsw scales: (v 128 g + 2^14) >> 15 =
// (v g + 128) >> 8, scaleQ8's rounding, from one multiply (v << 7 and g
// both fit signed 16 bits for g <= 32767). The rest is
// teach_x86::teachFour. Built only for x86 (the instructions are enabled per
// function); callers check the CPU first (boardTeachRow()). Elsewhere it is
// the C row.
#include "algo/board_teach_rows.hpp"

#if defined(__SSE2__) && (defined(__x86_64__) || defined(__i386__))
#define DEPTHKEY_BOARD_TEACH_SSSE3 1
#include "algo/board_teach_rows_x86.hpp"

#include <tmmintrin.h>
#define SSSE3 __attribute__((target("ssse3")))
#endif

namespace depthkey {

#if defined(DEPTHKEY_BOARD_TEACH_SSSE3)

namespace {

SSSE3 inline __m128i scaleQ8Lanes(__m128i v16, __m128i gain)
{
	return _mm_mulhrs_epi16(_mm_slli_epi16(v16, 7), gain);
}

} // namespace

SSSE3 void boardTeachRow_SSSE3(const Rgb8 *sampled, const uint8_t *mask, const int gainQ8[3], Rgba8 *model, int n,
			       BoardTeachSums &sums)
{
	const __m128i zero = _mm_setzero_si128();
	const __m128i gain = _mm_setr_epi16(int16_t(gainQ8[0]), int16_t(gainQ8[1]), int16_t(gainQ8[2]), 0,
					    int16_t(gainQ8[0]), int16_t(gainQ8[1]), int16_t(gainQ8[2]), 0);
	const __m128i spread = _mm_setr_epi8(0, 1, 2, -1, 3, 4, 5, -1, 6, 7, 8, -1, 9, 10, 11, -1);
	teach_x86::Sums acc;
	int x = 0;
	for (; x + 6 <= n; x += 4) {
		const __m128i rgba =
			_mm_shuffle_epi8(_mm_loadu_si128(reinterpret_cast<const __m128i *>(sampled + x)), spread);
		const __m128i predicted = _mm_packus_epi16(scaleQ8Lanes(_mm_unpacklo_epi8(rgba, zero), gain),
							   scaleQ8Lanes(_mm_unpackhi_epi8(rgba, zero), gain));
		teach_x86::teachFour(predicted, mask + x, model + x, acc);
	}
	acc.into(sums);
	boardTeachRow_C(sampled + x, mask + x, gainQ8, model + x, n - x, sums);
}

#else

void boardTeachRow_SSSE3(const Rgb8 *sampled, const uint8_t *mask, const int gainQ8[3], Rgba8 *model, int n,
			 BoardTeachSums &sums)
{
	boardTeachRow_C(sampled, mask, gainQ8, model, n, sums);
}

#endif

} // namespace depthkey
