#include "algo/mask_rows.hpp"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace depthkey {

void maskOrRow_C(uint8_t *acc, const uint8_t *src, int width)
{
	for (int x = 0; x < width; ++x)
		acc[x] |= src[x];
}

void maskAndRow_C(uint8_t *acc, const uint8_t *src, int width)
{
	for (int x = 0; x < width; ++x)
		acc[x] &= src[x];
}

#if defined(__SSE2__)

namespace {

template<typename VectorOp>
void combineRow(uint8_t *acc, const uint8_t *src, int width, VectorOp op, void (*tail)(uint8_t *, const uint8_t *, int))
{
	int x = 0;
	for (; x + 16 <= width; x += 16) {
		__m128i *a = reinterpret_cast<__m128i *>(acc + x);
		__m128i s = _mm_loadu_si128(reinterpret_cast<const __m128i *>(src + x));
		_mm_storeu_si128(a, op(_mm_loadu_si128(a), s));
	}
	tail(acc + x, src + x, width - x);
}

} // namespace

void maskOrRow_SSE2(uint8_t *acc, const uint8_t *src, int width)
{
	combineRow(acc, src, width, [](__m128i a, __m128i b) { return _mm_or_si128(a, b); }, maskOrRow_C);
}

void maskAndRow_SSE2(uint8_t *acc, const uint8_t *src, int width)
{
	combineRow(acc, src, width, [](__m128i a, __m128i b) { return _mm_and_si128(a, b); }, maskAndRow_C);
}

#else

void maskOrRow_SSE2(uint8_t *acc, const uint8_t *src, int width) { maskOrRow_C(acc, src, width); }
void maskAndRow_SSE2(uint8_t *acc, const uint8_t *src, int width) { maskAndRow_C(acc, src, width); }

#endif

MaskRowFn maskRow(KernelPath path, bool erode)
{
	if (sse2Rows(path))
		return erode ? maskAndRow_SSE2 : maskOrRow_SSE2;
	if (path == KernelPath::Neon)
		return erode ? maskAndRow_NEON : maskOrRow_NEON;
	return erode ? maskAndRow_C : maskOrRow_C;
}

} // namespace depthkey
