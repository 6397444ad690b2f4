// SSE2 helpers shared by the row kernels that read packed RGB24 (the
// composite's lecturer layer, the virtual webcam's YUYV conversion). Only
// for files built with SSE2 (x86-64); each includes it inside its own
// `#if defined(__SSE2__)`.
#pragma once

#include <emmintrin.h>

namespace depthkey {

// 4 RGB pixels (the low 12 bytes of v) spread to 4 32-bit lanes R G B 0:
// pixel k moves up k bytes, then each lane keeps its low three bytes.
inline __m128i rgbToRgbx(__m128i v)
{
	const __m128i lane0 = _mm_setr_epi32(0x00ffffff, 0, 0, 0), lane1 = _mm_setr_epi32(0, 0x00ffffff, 0, 0);
	const __m128i lane2 = _mm_setr_epi32(0, 0, 0x00ffffff, 0), lane3 = _mm_setr_epi32(0, 0, 0, 0x00ffffff);
	__m128i p = _mm_and_si128(v, lane0);
	p = _mm_or_si128(p, _mm_and_si128(_mm_slli_si128(v, 1), lane1));
	p = _mm_or_si128(p, _mm_and_si128(_mm_slli_si128(v, 2), lane2));
	return _mm_or_si128(p, _mm_and_si128(_mm_slli_si128(v, 3), lane3));
}

} // namespace depthkey
