// SSE2 row of algo/luma_rows.hpp, sixteen pixels a step: each group of four
// spread to one 32-bit lane a pixel (rgbToRgbx, a 16-byte load of which 12
// bytes are the group's, so the step runs while 18 pixels remain), the
// luma summed in the lane and packed back to bytes; the rest go through the
// C row. Built without SSE2 (not x86-64) it is the C row.
#include "algo/luma_rows.hpp"

#if defined(__SSE2__)
#include "algo/rgb_lanes_sse2.hpp"
#endif

namespace depthkey {

#if defined(__SSE2__)

namespace {

// (R + 2 G + B + 2) >> 2 of four pixels, one a 32-bit lane.
inline __m128i lumaOfFour(const Rgb8 *colour)
{
	const __m128i v = rgbToRgbx(_mm_loadu_si128(reinterpret_cast<const __m128i *>(colour)));
	const __m128i low = _mm_set1_epi32(0xff);
	const __m128i r = _mm_and_si128(v, low), g = _mm_and_si128(_mm_srli_epi32(v, 8), low);
	const __m128i b = _mm_srli_epi32(v, 16); // the lane's fourth byte is 0
	const __m128i sum = _mm_add_epi32(_mm_add_epi32(r, b), _mm_add_epi32(_mm_add_epi32(g, g), _mm_set1_epi32(2)));
	return _mm_srli_epi32(sum, 2);
}

} // namespace

void lumaRow_SSE2(const Rgb8 *colour, int n, uint8_t *luma)
{
	int x = 0;
	for (; x + 18 <= n; x += 16) {
		const __m128i low = _mm_packs_epi32(lumaOfFour(colour + x), lumaOfFour(colour + x + 4));
		const __m128i high = _mm_packs_epi32(lumaOfFour(colour + x + 8), lumaOfFour(colour + x + 12));
		_mm_storeu_si128(reinterpret_cast<__m128i *>(luma + x), _mm_packus_epi16(low, high));
	}
	lumaRow_C(colour + x, n - x, luma + x);
}

#else

void lumaRow_SSE2(const Rgb8 *colour, int n, uint8_t *luma)
{
	lumaRow_C(colour, n, luma);
}

#endif

} // namespace depthkey
