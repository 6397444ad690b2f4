// Row kernels for the fused evidence's arithmetic terms (issue 28: the
// evidence row was about 100 instructions a band pixel, a third of them
// these two sums). For a span of the colour row:
//   board distance: the L1 distance of the colour to the board model's
//     colour times the light's gain, round(m g / 256) per channel, as
//     BoardModel::distance() gives it (-1 where the model has fewer than
//     BoardModel::kLearnedVisits visits);
//   colour change: the L1 distance of the colour to the previous frame's;
//   still hold: the two stamps per pixel of FusedEvidence's hold through a
//     writing hand's still moments (the frame the colour last moved in, the
//     last frame depth saw him in front), and whether the pixel is held.
// The table lookups that remain (the SIOX decision, the board and depth
// terms) stay in FusedEvidence's scalar loop. A plain C reference (_C) and
// SSE2 and NEON rows (evidence_terms_rows_sse2.cpp, _neon.cpp) that give the
// C row's values for any bytes and any gain of 0..1023 (Q8)
// (tests/evidence_terms_rows_test.cpp).
#pragma once

#include "algo/image.hpp"
#include "algo/kernel_path.hpp"

#include <cstdint>

namespace depthkey {

// The visits a model pixel needs before its distance counts (the same as
// BoardModel::kLearnedVisits; the kernels are kept free of that class).
inline constexpr uint8_t kEvidenceLearnedVisits = 2;

// distance[x] for x in [0, n); gainQ8 per channel R, G, B, each 0..1023
// (BoardModel's gains are 128..512).
void boardDistanceRow_C(const Rgb8 *colour, const Rgba8 *model, const int gainQ8[3], int n, int16_t *distance);
void boardDistanceRow_SSE2(const Rgb8 *colour, const Rgba8 *model, const int gainQ8[3], int n, int16_t *distance);
void boardDistanceRow_NEON(const Rgb8 *colour, const Rgba8 *model, const int gainQ8[3], int n, int16_t *distance);
using BoardDistanceFn = void (*)(const Rgb8 *, const Rgba8 *, const int[3], int, int16_t *);
BoardDistanceFn boardDistanceRow(KernelPath path);

// change[x] = |R - R'| + |G - G'| + |B - B'| for x in [0, n).
void colourChangeRow_C(const Rgb8 *colour, const Rgb8 *previous, int n, int16_t *change);
void colourChangeRow_SSE2(const Rgb8 *colour, const Rgb8 *previous, int n, int16_t *change);
void colourChangeRow_NEON(const Rgb8 *colour, const Rgb8 *previous, int n, int16_t *change);
using ColourChangeFn = void (*)(const Rgb8 *, const Rgb8 *, int, int16_t *);
ColourChangeFn colourChangeRow(KernelPath path);

// For x in [0, n): moved[x] = frame where change[x] >= still (1..765), and
// inFront[x] = frame where evidence[x] > pivot (0..254); then held[x] = 1
// where frame - moved[x] < holdFrames and frame - inFront[x] >= holdFrames
// (ages mod 2^16; holdFrames 1..32767), else 0.
struct StillHold {
	int still, pivot, holdFrames;
	uint16_t frame;
};
void stillHoldRow_C(const int16_t *change, const uint8_t *evidence, int n, const StillHold &h, uint16_t *moved,
		    uint16_t *inFront, uint8_t *held);
void stillHoldRow_SSE2(const int16_t *change, const uint8_t *evidence, int n, const StillHold &h, uint16_t *moved,
		       uint16_t *inFront, uint8_t *held);
void stillHoldRow_NEON(const int16_t *change, const uint8_t *evidence, int n, const StillHold &h, uint16_t *moved,
		       uint16_t *inFront, uint8_t *held);
using StillHoldFn = void (*)(const int16_t *, const uint8_t *, int, const StillHold &, uint16_t *, uint16_t *,
			     uint8_t *);
StillHoldFn stillHoldRow(KernelPath path);

} // namespace depthkey
