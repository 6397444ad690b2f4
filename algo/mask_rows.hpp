// Row kernels of 0 / 255 masks for the morphology: acc = acc | src (dilate)
// or acc = acc & src (erode), byte by byte. A plain C reference (_C), SSE2
// and NEON (algo/mask_rows_neon.cpp; 16 bytes per instruction, unaligned,
// tail in C) that give the same bytes (tests/morphology_test.cpp compares them).
#pragma once

#include "algo/kernel_path.hpp"

#include <cstdint>

namespace depthkey {

void maskOrRow_C(uint8_t *acc, const uint8_t *src, int width);
void maskAndRow_C(uint8_t *acc, const uint8_t *src, int width);
void maskOrRow_SSE2(uint8_t *acc, const uint8_t *src, int width);
void maskAndRow_SSE2(uint8_t *acc, const uint8_t *src, int width);
void maskOrRow_NEON(uint8_t *acc, const uint8_t *src, int width);
void maskAndRow_NEON(uint8_t *acc, const uint8_t *src, int width);

// One of the six, chosen once per image.
using MaskRowFn = void (*)(uint8_t *acc, const uint8_t *src, int width);
MaskRowFn maskRow(KernelPath path, bool erode);

} // namespace depthkey
