// SSE2 row of algo/max_paint_rows.hpp: 16 bytes a step with an unsigned
// byte max; the last step's value is masked to the lanes below n, so the
// bytes beyond keep theirs (max with 0). Without room for a 16-byte step the
// tail goes through the C row. Built without SSE2 (not x86-64) it is the C
// row.
#include "algo/max_paint_rows.hpp"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace depthkey {

#if defined(__SSE2__)

void maxPaintRow_SSE2(uint8_t *row, int n, int room, uint8_t value)
{
	const __m128i v = _mm_set1_epi8(char(value));
	int x = 0;
	for (; x + 16 <= n; x += 16) {
		__m128i *p = reinterpret_cast<__m128i *>(row + x);
		_mm_storeu_si128(p, _mm_max_epu8(_mm_loadu_si128(p), v));
	}
	if (x == n)
		return;
	if (x + 16 > room) {
		maxPaintRow_C(row + x, n - x, room - x, value);
		return;
	}
	const __m128i mask = _mm_loadu_si128(reinterpret_cast<const __m128i *>(kFirstLanesMask + 16 - (n - x)));
	__m128i *p = reinterpret_cast<__m128i *>(row + x);
	_mm_storeu_si128(p, _mm_max_epu8(_mm_loadu_si128(p), _mm_and_si128(v, mask)));
}

#else

void maxPaintRow_SSE2(uint8_t *row, int n, int room, uint8_t value) { maxPaintRow_C(row, n, room, value); }

#endif

} // namespace depthkey
