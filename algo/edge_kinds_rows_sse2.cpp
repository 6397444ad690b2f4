// SSE2 row of algo/edge_kinds_rows.hpp: sixteen pixels a step (unaligned
// loads within [-1, n]), the five bytes summed in 16-bit lanes and
// compared with 5 * 255 and 0, the masks packed back to bytes; fewer than
// sixteen left go through the C row. Built without SSE2 it is the C row.
#include "algo/edge_kinds_rows.hpp"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace depthkey {

#if defined(__SSE2__)

void edgeKindsRow_SSE2(const uint8_t *up, const uint8_t *m, const uint8_t *down, int n, uint8_t *kinds)
{
	auto load = [](const uint8_t *p) { return _mm_loadu_si128(reinterpret_cast<const __m128i *>(p)); };
	const __m128i zero = _mm_setzero_si128(), full = _mm_set1_epi16(5 * 255), one = _mm_set1_epi8(1);
	const __m128i lecturerInside = _mm_set1_epi8(char(kEdgeKindLecturerInside));
	const __m128i boardInside = _mm_set1_epi8(char(kEdgeKindBoardInside));
	int x = 0;
	for (; x + 16 <= n; x += 16) {
		const __m128i v[5] = { load(m + x), load(m + x - 1), load(m + x + 1), load(up + x), load(down + x) };
		__m128i lo = zero, hi = zero;
		for (const __m128i &b : v) {
			lo = _mm_add_epi16(lo, _mm_unpacklo_epi8(b, zero));
			hi = _mm_add_epi16(hi, _mm_unpackhi_epi8(b, zero));
		}
		// 0xff where all five are 255, where all are 0.
		const __m128i allOn = _mm_packs_epi16(_mm_cmpeq_epi16(lo, full), _mm_cmpeq_epi16(hi, full));
		const __m128i allOff = _mm_packs_epi16(_mm_cmpeq_epi16(lo, zero), _mm_cmpeq_epi16(hi, zero));
		const __m128i lecturerEdge = _mm_andnot_si128(_mm_cmpeq_epi8(v[0], zero), one); // 1 where m != 0
		const __m128i edge = _mm_andnot_si128(_mm_or_si128(allOn, allOff), lecturerEdge);
		const __m128i kind = _mm_or_si128(
			edge, _mm_or_si128(_mm_and_si128(allOn, lecturerInside), _mm_and_si128(allOff, boardInside)));
		_mm_storeu_si128(reinterpret_cast<__m128i *>(kinds + x), kind);
	}
	edgeKindsRow_C(up + x, m + x, down + x, n - x, kinds + x);
}

#else

void edgeKindsRow_SSE2(const uint8_t *up, const uint8_t *m, const uint8_t *down, int n, uint8_t *kinds)
{
	edgeKindsRow_C(up, m, down, n, kinds);
}

#endif

} // namespace depthkey
