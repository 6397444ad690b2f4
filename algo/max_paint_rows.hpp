// The seed mapper's block painting (algo/seed_mapper.cpp): every byte of
// row[0, n) becomes max(byte, value) — "nearest wins" for trimap labels and
// depth evidence where blocks of neighbouring ToF pixels overlap. A block
// is a few to a dozen colour pixels wide (its ToF pixel's footprint), so
// the SIMD rows paint 16 bytes at once under a mask of the first n lanes:
// max(byte, value & mask), which leaves the bytes beyond n as they were.
// They therefore read and rewrite 16 bytes from row, and need room >= 16
// bytes of the row there (room: bytes from row to the row's end); with
// less they paint the tail in C. The rewritten bytes beyond n are unchanged,
// but written: no other thread may paint the same row at once. A plain C
// reference (_C) and SSE2 and NEON variants (max_paint_rows_sse2.cpp,
// max_paint_rows_neon.cpp) that paint the same bytes for any n, room and
// alignment (tests/max_paint_rows_test.cpp).
#pragma once

#include "algo/kernel_path.hpp"

#include <cstdint>

namespace depthkey {

void maxPaintRow_C(uint8_t *row, int n, int room, uint8_t value);
void maxPaintRow_SSE2(uint8_t *row, int n, int room, uint8_t value);
void maxPaintRow_NEON(uint8_t *row, int n, int room, uint8_t value);

// The mask of the first n lanes of 16 (0 <= n <= 16) from kFirstLanesMask + 16 - n.
extern const uint8_t kFirstLanesMask[32];

// One of the three, chosen once per image.
using MaxPaintFn = void (*)(uint8_t *row, int n, int room, uint8_t value);
MaxPaintFn maxPaintRow(KernelPath path);

} // namespace depthkey
