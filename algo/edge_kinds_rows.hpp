// The boundary unmixing's pixel kinds (algo/boundary_unmixing.hpp), a row at
// a time (issue 28: found over the whole ROI once a frame, the stage's one
// whole-ROI pass): from the sum of a pixel's and its four neighbours'
// matte, kEdgeKindLecturerInside where all five are 255, kEdgeKindBoardInside
// where all are 0, else kEdgeKindLecturerEdge or kEdgeKindBoardEdge by the
// pixel's own matte. A plain C reference (_C) and SSE2 and NEON rows
// (edge_kinds_rows_sse2.cpp, edge_kinds_rows_neon.cpp) that sum in 16 bits,
// so they give the C row's kinds for any matte bytes
// (tests/edge_kinds_rows_test.cpp).
#pragma once

#include "algo/kernel_path.hpp"

#include <cstdint>

namespace depthkey {

inline constexpr uint8_t kEdgeKindBoardEdge = 0, kEdgeKindLecturerEdge = 1, kEdgeKindLecturerInside = 2,
			 kEdgeKindBoardInside = 3;

inline uint8_t edgeKindOf(int around, uint8_t m)
{
	return around == 5 * 255 ? kEdgeKindLecturerInside
	       : around == 0     ? kEdgeKindBoardInside
	       : m               ? kEdgeKindLecturerEdge
				 : kEdgeKindBoardEdge;
}

// kinds[x] for x in [0, n), from the matte rows up, m and down; reads
// m[-1] and m[n] (the caller's neighbours).
void edgeKindsRow_C(const uint8_t *up, const uint8_t *m, const uint8_t *down, int n, uint8_t *kinds);
void edgeKindsRow_SSE2(const uint8_t *up, const uint8_t *m, const uint8_t *down, int n, uint8_t *kinds);
void edgeKindsRow_NEON(const uint8_t *up, const uint8_t *m, const uint8_t *down, int n, uint8_t *kinds);
using EdgeKindsFn = void (*)(const uint8_t *, const uint8_t *, const uint8_t *, int, uint8_t *);
EdgeKindsFn edgeKindsRow(KernelPath path);

} // namespace depthkey
