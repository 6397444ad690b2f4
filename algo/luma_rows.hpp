// The guided filter's guide, a row at a time (issue 28: the one pass of the
// filter over the whole ROI, about 10 instructions a pixel as plain C):
// luma (R + 2 G + B + 2) >> 2 of each RGB pixel. A plain C reference (_C)
// and SSE2 and NEON rows (luma_rows_sse2.cpp, luma_rows_neon.cpp) that give
// the C row's bytes for any pixels (tests/luma_rows_test.cpp).
#pragma once

#include "algo/image.hpp"
#include "algo/kernel_path.hpp"

#include <cstdint>

namespace depthkey {

// luma[x] for x in [0, n).
void lumaRow_C(const Rgb8 *colour, int n, uint8_t *luma);
void lumaRow_SSE2(const Rgb8 *colour, int n, uint8_t *luma);
void lumaRow_NEON(const Rgb8 *colour, int n, uint8_t *luma);
using LumaFn = void (*)(const Rgb8 *, int, uint8_t *);
LumaFn lumaRow(KernelPath path);

} // namespace depthkey
