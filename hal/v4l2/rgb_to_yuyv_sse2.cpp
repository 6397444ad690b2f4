// The SSE2 row of hal/v4l2/rgb_to_yuyv.hpp: the same bytes as
// rgbToYuyvRow_C for any width and alignment (unaligned loads and stores;
// the tail goes through the C row). Built without SSE2 it is the C row.
//
// Four pixels (two pairs) a step, in 32-bit arithmetic as the C row:
// - the 12 bytes are spread to one 32-bit lane per pixel, R G B and G again
//   in the fourth byte, then widened to 16-bit lanes, two pixels a register;
// - luma: pmaddwd with (kYr, kYg1, kYb, kYg2), kYg1 + kYg2 = kYg = 33039
//   (too big for a signed 16-bit factor, so G is counted twice with halves),
//   and the two 32-bit partial sums of each pixel added;
// - chroma: the pair's two pixels added in 16-bit lanes (<= 510), pmaddwd
//   with (kUr, kUg, kUb, 0) and (kVr, kVg, kVb, 0), the partial sums added;
// - the same biases and shifts as the C row, so the same integers, packed.
#include "hal/v4l2/rgb_to_yuyv.hpp"

#include "hal/v4l2/rgb_to_yuyv_coefficients.hpp"

#if defined(__SSE2__)
#include "algo/rgb_lanes_sse2.hpp"
#endif

namespace depthkey {

#if defined(__SSE2__)

namespace {

using namespace yuyv;

constexpr int kYg1 = 16520, kYg2 = kYg - kYg1; // 16519
static_assert(kYg1 <= 32767 && kYg2 <= 32767);

// 4 RGB pixels (the low 12 bytes of v) spread to 4 lanes R G B G.
inline __m128i rgbToRgbg(__m128i v)
{
	const __m128i p = rgbToRgbx(v);
	return _mm_or_si128(p, _mm_slli_epi32(_mm_and_si128(p, _mm_set1_epi32(0x0000ff00)), 16));
}

// Each 32-bit lane plus its neighbour in the pair (0+1, 2+3).
inline __m128i addPairs(__m128i v)
{
	return _mm_add_epi32(v, _mm_shuffle_epi32(v, _MM_SHUFFLE(2, 3, 0, 1)));
}

// One pair's two pixels as 16-bit lanes R0 G0 B0 G0 R1 G1 B1 G1 -> 32-bit
// lanes Y0 U Y1 V.
inline __m128i pairToYuyv(__m128i px)
{
	const __m128i yCoef = _mm_setr_epi16(kYr, kYg1, kYb, kYg2, kYr, kYg1, kYb, kYg2);
	const __m128i uvCoef = _mm_setr_epi16(kUr, kUg, kUb, 0, kVr, kVg, kVb, 0);
	const __m128i even = _mm_setr_epi32(-1, 0, -1, 0);
	__m128i y = addPairs(_mm_madd_epi16(px, yCoef));                     // Y0 Y0 Y1 Y1 (unshifted)
	y = _mm_srli_epi32(_mm_add_epi32(y, _mm_set1_epi32(kLumaBias)), 16);
	__m128i sum = _mm_add_epi16(px, _mm_srli_si128(px, 8));              // pair sum in lanes 0..3
	__m128i uv = addPairs(_mm_madd_epi16(_mm_unpacklo_epi64(sum, sum), uvCoef)); // U U V V
	uv = _mm_srai_epi32(_mm_add_epi32(uv, _mm_set1_epi32(kChromaBias)), 17);
	return _mm_or_si128(_mm_and_si128(even, y), _mm_andnot_si128(even, uv));
}

} // namespace

void rgbToYuyvRow_SSE2(const Rgb8 *rgb, uint8_t *out, int width)
{
	const __m128i zero = _mm_setzero_si128();
	const uint8_t *in = reinterpret_cast<const uint8_t *>(rgb);
	int x = 0;
	// A 16-byte load reads 4 bytes past the 4 pixels: stay 6 pixels inside.
	for (; x + 6 <= width; x += 4) {
		__m128i p = rgbToRgbg(_mm_loadu_si128(reinterpret_cast<const __m128i *>(in + 3 * x)));
		__m128i first = pairToYuyv(_mm_unpacklo_epi8(p, zero));
		__m128i second = pairToYuyv(_mm_unpackhi_epi8(p, zero));
		__m128i bytes = _mm_packus_epi16(_mm_packs_epi32(first, second), zero);
		_mm_storel_epi64(reinterpret_cast<__m128i *>(out + 2 * x), bytes);
	}
	rgbToYuyvRow_C(rgb + x, out + 2 * x, width - x); // x is even: pairs stay pairs
}

#else

void rgbToYuyvRow_SSE2(const Rgb8 *rgb, uint8_t *out, int width) { rgbToYuyvRow_C(rgb, out, width); }

#endif

} // namespace depthkey
