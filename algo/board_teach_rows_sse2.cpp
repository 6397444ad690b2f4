// SSE2 row of algo/board_teach_rows.hpp: four pixels a step. The sampled
// RGB bytes are spread to RGBA with byte shifts (pixel k's three bytes sit
// at 3k, and a whole-register shift left by k bytes puts them at 4k), and
// scaled in 16-bit lanes: v * g is split into its low and high halves
// (mullo, mulhi), and (v g + 128) >> 8 = (hi << 8) + (((lo >> 1) + 64) >> 7)
// (the half dropped by lo >> 1 never carries past a multiple of 128); the
// pack to bytes saturates at 255 as scaleQ8's min does. The rest is
// teach_x86::teachFour. Fewer than six pixels left (a step reads 16 bytes
// of RGB) go through the C row. Built without SSE2 it is the C row.
#include "algo/board_teach_rows.hpp"

#if defined(__SSE2__)
#include "algo/board_teach_rows_x86.hpp"
#endif

namespace depthkey {

#if defined(__SSE2__)

void boardTeachRow_SSE2(const Rgb8 *sampled, const uint8_t *mask, const int gainQ8[3], Rgba8 *model, int n,
			BoardTeachSums &sums)
{
	const __m128i zero = _mm_setzero_si128();
	const __m128i gain = _mm_setr_epi16(int16_t(gainQ8[0]), int16_t(gainQ8[1]), int16_t(gainQ8[2]), 0,
					    int16_t(gainQ8[0]), int16_t(gainQ8[1]), int16_t(gainQ8[2]), 0);
	const __m128i sixtyFour = _mm_set1_epi16(64);
	const __m128i lane0 = _mm_setr_epi32(0x00ffffff, 0, 0, 0), lane1 = _mm_setr_epi32(0, 0x00ffffff, 0, 0);
	const __m128i lane2 = _mm_setr_epi32(0, 0, 0x00ffffff, 0), lane3 = _mm_setr_epi32(0, 0, 0, 0x00ffffff);
	auto scale = [&](__m128i v16) {
		const __m128i lo = _mm_mullo_epi16(v16, gain), hi = _mm_mulhi_epu16(v16, gain);
		return _mm_add_epi16(_mm_slli_epi16(hi, 8), _mm_srli_epi16(_mm_add_epi16(_mm_srli_epi16(lo, 1), sixtyFour), 7));
	};
	teach_x86::Sums acc;
	int x = 0;
	for (; x + 6 <= n; x += 4) {
		const __m128i rgb = _mm_loadu_si128(reinterpret_cast<const __m128i *>(sampled + x));
		const __m128i rgba = _mm_or_si128(
			_mm_or_si128(_mm_and_si128(rgb, lane0), _mm_and_si128(_mm_slli_si128(rgb, 1), lane1)),
			_mm_or_si128(_mm_and_si128(_mm_slli_si128(rgb, 2), lane2), _mm_and_si128(_mm_slli_si128(rgb, 3), lane3)));
		const __m128i predicted = _mm_packus_epi16(scale(_mm_unpacklo_epi8(rgba, zero)),
							   scale(_mm_unpackhi_epi8(rgba, zero)));
		teach_x86::teachFour(predicted, mask + x, model + x, acc);
	}
	acc.into(sums);
	boardTeachRow_C(sampled + x, mask + x, gainQ8, model + x, n - x, sums);
}

#else

void boardTeachRow_SSE2(const Rgb8 *sampled, const uint8_t *mask, const int gainQ8[3], Rgba8 *model, int n,
			BoardTeachSums &sums)
{
	boardTeachRow_C(sampled, mask, gainQ8, model, n, sums);
}

#endif

} // namespace depthkey
