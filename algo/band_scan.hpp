// The SIOX refiner's band scan (algo/siox_refiner.cpp): in a row of trimap
// labels, the first x in [x, end) that is not a seed (neither
// kTrimapBoard nor kTrimapLecturer), or end. Most of a ROI is seeds, so the
// SIMD rows test 16 labels at once. A plain C reference (_C) and SSE2 and
// NEON variants (band_scan_sse2.cpp, band_scan_neon.cpp) that give the same
// x for any row and alignment (tests/band_scan_test.cpp).
#pragma once

#include "algo/kernel_path.hpp"
#include "algo/trimap.hpp"

#include <cstdint>

namespace depthkey {

inline bool isTrimapSeed(uint8_t label) { return label == kTrimapBoard || label == kTrimapLecturer; }

int nextUndecidedRow_C(const uint8_t *labels, int x, int end);
int nextUndecidedRow_SSE2(const uint8_t *labels, int x, int end);
int nextUndecidedRow_NEON(const uint8_t *labels, int x, int end);

// One of the three, chosen once per image.
using BandScanFn = int (*)(const uint8_t *labels, int x, int end);
BandScanFn bandScanRow(KernelPath path);

} // namespace depthkey
