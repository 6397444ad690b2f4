// SSE2 rows of algo/board_learn_rows.hpp. The learn row is four pixels a
// step: the colour's RGB bytes spread to RGBA (alpha 0) by byte shifts
// (pixel k's three bytes sit at 3k; the register shifted left by k bytes
// puts them at 4k), then teach_x86::teachFour, the teach row's step, which at
// unit gain is exactly learn's. Fewer than six pixels left (a step reads 16
// bytes of RGB) go through the C row. The OR and select rows are sixteen
// bytes a step, the rest through the C rows. Built only for SSE2
// (boardLearnRows() gives the C rows elsewhere).
#if defined(__SSE2__)

#include "algo/board_learn_rows.hpp"

#include "algo/board_teach_rows_x86.hpp"
#include "algo/trimap.hpp"

namespace depthkey {

namespace {

__m128i load16(const uint8_t *p) { return _mm_loadu_si128(reinterpret_cast<const __m128i *>(p)); }

} // namespace

void boardLearnRow_SSE2(const Rgb8 *colour, const uint8_t *trimap, Rgba8 *model, int n, BoardTeachSums &sums)
{
	const __m128i pixel0 = _mm_setr_epi32(0x00ffffff, 0, 0, 0), pixel1 = _mm_slli_si128(pixel0, 4);
	const __m128i pixel2 = _mm_slli_si128(pixel0, 8), pixel3 = _mm_slli_si128(pixel0, 12);
	teach_x86::Sums acc;
	int x = 0;
	for (; x + 6 <= n; x += 4) {
		const __m128i rgb = load16(reinterpret_cast<const uint8_t *>(colour + x));
		const __m128i first = _mm_or_si128(_mm_and_si128(rgb, pixel0), _mm_and_si128(_mm_slli_si128(rgb, 1), pixel1));
		const __m128i last = _mm_or_si128(_mm_and_si128(_mm_slli_si128(rgb, 2), pixel2),
						  _mm_and_si128(_mm_slli_si128(rgb, 3), pixel3));
		teach_x86::teachFour(_mm_or_si128(first, last), trimap + x, model + x, acc);
	}
	acc.into(sums);
	boardLearnRow_C(colour + x, trimap + x, model + x, n - x, sums);
}

void boardAlphaOrRow_SSE2(const uint8_t *a, const uint8_t *b, const uint8_t *c, uint8_t *out, int n)
{
	int x = 0;
	for (; x + 16 <= n; x += 16)
		_mm_storeu_si128(reinterpret_cast<__m128i *>(out + x),
				 _mm_or_si128(_mm_or_si128(load16(a + x), load16(b + x)), load16(c + x)));
	boardAlphaOrRow_C(a + x, b + x, c + x, out + x, n - x);
}

void boardDecidedSelectRow_SSE2(const uint8_t *near, const uint8_t *trimap, int margin, uint8_t *select, int n)
{
	const __m128i zero = _mm_setzero_si128(), lecturer = _mm_set1_epi8(char(kTrimapLecturer));
	static_assert(kTrimapBoard == 0 && kTrimapLecturer == 0xff, "select bytes are the compare masks");
	int x = 0;
	for (; x + 16 <= n; x += 16) {
		const __m128i any = _mm_or_si128(_mm_or_si128(load16(near + x - margin), load16(near + x)),
						 load16(near + x + margin));
		const __m128i t = load16(trimap + x);
		// Not learned: board or lecturer in the trimap, or a lecturer pixel near.
		const __m128i kept = _mm_or_si128(_mm_or_si128(_mm_cmpeq_epi8(t, zero), _mm_cmpeq_epi8(t, lecturer)),
						  _mm_andnot_si128(_mm_cmpeq_epi8(any, zero), lecturer));
		_mm_storeu_si128(reinterpret_cast<__m128i *>(select + x), kept);
	}
	boardDecidedSelectRow_C(near + x, trimap + x, margin, select + x, n - x);
}

} // namespace depthkey

#endif
