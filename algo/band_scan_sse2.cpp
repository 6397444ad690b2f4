// SSE2 row of algo/band_scan.hpp: 16 labels a compare (unaligned loads
// within [x, end)), the first non-seed from the movemask's lowest clear
// bit; fewer than 16 left go through the C row. Built without SSE2 (not
// x86-64) it is the C row.
#include "algo/band_scan.hpp"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace depthkey {

#if defined(__SSE2__)

int nextUndecidedRow_SSE2(const uint8_t *labels, int x, int end)
{
	const __m128i board = _mm_set1_epi8(char(kTrimapBoard)), lecturer = _mm_set1_epi8(char(kTrimapLecturer));
	for (; x + 16 <= end; x += 16) {
		__m128i v = _mm_loadu_si128(reinterpret_cast<const __m128i *>(labels + x));
		int seeds = _mm_movemask_epi8(_mm_or_si128(_mm_cmpeq_epi8(v, board), _mm_cmpeq_epi8(v, lecturer)));
		if (seeds != 0xffff)
			return x + __builtin_ctz(~seeds);
	}
	return nextUndecidedRow_C(labels, x, end);
}

#else

int nextUndecidedRow_SSE2(const uint8_t *labels, int x, int end) { return nextUndecidedRow_C(labels, x, end); }

#endif

} // namespace depthkey
