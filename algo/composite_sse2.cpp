// SSE2 rows of algo/composite.hpp: the same bytes as the _C rows for any
// width and alignment (unaligned loads and stores; the tail goes through the
// C row). Built without SSE2 (not x86-64) they are the C rows.
#include "algo/composite.hpp"

#if defined(__SSE2__)
#include "algo/rgb_lanes_sse2.hpp"
#endif

namespace depthkey {

#if defined(__SSE2__)

namespace {

// 16 bytes of board and lecturer blended with one weight w (0..256):
// (b * (256 - w) + l * w + 128) >> 8 in 16-bit lanes. The sum is at most
// 255 * 256 + 128 = 65408, so unsigned 16-bit lanes never overflow.
inline __m128i blend16(__m128i board, __m128i lecturer, __m128i w, __m128i wb)
{
	const __m128i zero = _mm_setzero_si128(), half = _mm_set1_epi16(128);
	__m128i lo = _mm_add_epi16(_mm_mullo_epi16(_mm_unpacklo_epi8(board, zero), wb),
				   _mm_mullo_epi16(_mm_unpacklo_epi8(lecturer, zero), w));
	__m128i hi = _mm_add_epi16(_mm_mullo_epi16(_mm_unpackhi_epi8(board, zero), wb),
				   _mm_mullo_epi16(_mm_unpackhi_epi8(lecturer, zero), w));
	lo = _mm_srli_epi16(_mm_add_epi16(lo, half), 8);
	hi = _mm_srli_epi16(_mm_add_epi16(hi, half), 8);
	return _mm_packus_epi16(lo, hi);
}

inline __m128i load(const void *p) { return _mm_loadu_si128(static_cast<const __m128i *>(p)); }
inline void store(void *p, __m128i v) { _mm_storeu_si128(static_cast<__m128i *>(p), v); }

} // namespace

// Without SSSE3 there is no byte shuffle to spread a per-pixel weight over
// the three bytes of an RGB pixel. But the matte is flat almost everywhere
// (0 off the lecturer, 255 on it); only the soft edge varies. So a block of
// 16 pixels whose alpha is all one value is blended as 48 bytes with one
// weight, and the rare mixed block goes through the C row.
void compositeRow_SSE2(const Rgb8 *lecturer, const uint8_t *alpha, const Rgb8 *board,
		       int opacityQ8, Rgb8 *out, int width)
{
	int x = 0;
	for (; x + 16 <= width; x += 16) {
		__m128i a = load(alpha + x);
		__m128i first = _mm_set1_epi8(static_cast<char>(alpha[x]));
		if (_mm_movemask_epi8(_mm_cmpeq_epi8(a, first)) != 0xffff) {
			compositeRow_C(lecturer + x, alpha + x, board + x, opacityQ8, out + x, 16);
			continue;
		}
		unsigned weight = compositeWeight(opacityQ8, alpha[x]);
		__m128i w = _mm_set1_epi16(static_cast<short>(weight));
		__m128i wb = _mm_set1_epi16(static_cast<short>(256u - weight));
		const uint8_t *l = &lecturer[x].r, *b = &board[x].r;
		uint8_t *o = &out[x].r;
		for (int k = 0; k < 48; k += 16)
			store(o + k, blend16(load(b + k), load(l + k), w, wb));
	}
	compositeRow_C(lecturer + x, alpha + x, board + x, opacityQ8, out + x, width - x);
}

void lecturerLayerRow_SSE2(const Rgb8 *colour, const uint8_t *alpha, Rgba8 *out, int width)
{
	const __m128i zero = _mm_setzero_si128();
	int x = 0;
	// Each group of 4 pixels is read with a 16-byte load of which 12 bytes
	// are used, so the last load of a block reads 4 bytes past it: the
	// vector loop stops while at least 2 pixels (6 bytes) follow.
	for (; x + 18 <= width; x += 16) {
		const uint8_t *c = &colour[x].r;
		// Alpha into byte 3 of each 32-bit lane: interleave zeros below it twice.
		__m128i a = load(alpha + x);
		__m128i a8lo = _mm_unpacklo_epi8(zero, a), a8hi = _mm_unpackhi_epi8(zero, a);
		uint8_t *o = &out[x].r;
		store(o, _mm_or_si128(rgbToRgbx(load(c)), _mm_unpacklo_epi16(zero, a8lo)));
		store(o + 16, _mm_or_si128(rgbToRgbx(load(c + 12)), _mm_unpackhi_epi16(zero, a8lo)));
		store(o + 32, _mm_or_si128(rgbToRgbx(load(c + 24)), _mm_unpacklo_epi16(zero, a8hi)));
		store(o + 48, _mm_or_si128(rgbToRgbx(load(c + 36)), _mm_unpackhi_epi16(zero, a8hi)));
	}
	lecturerLayerRow_C(colour + x, alpha + x, out + x, width - x);
}

#else

void compositeRow_SSE2(const Rgb8 *lecturer, const uint8_t *alpha, const Rgb8 *board,
		       int opacityQ8, Rgb8 *out, int width)
{
	compositeRow_C(lecturer, alpha, board, opacityQ8, out, width);
}

void lecturerLayerRow_SSE2(const Rgb8 *colour, const uint8_t *alpha, Rgba8 *out, int width)
{
	lecturerLayerRow_C(colour, alpha, out, width);
}

#endif

} // namespace depthkey
