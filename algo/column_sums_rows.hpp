// Row kernels that move the column sums of algo/column_sums.hpp down one row
// (issue 28): for a run of columns that held row y - 1's window, add the
// values of the row coming in and take off those of the row going out, all
// modulo 2^32 (as ColumnSums::bring does one column at a time, so the sums
// are the same bit for bit). A row that is not there (beyond the ROI) is
// passed as a row of zeros. A plain C reference (_C) and SSE2 and NEON rows
// (column_sums_rows_sse2.cpp, column_sums_rows_neon.cpp) that give the same
// sums for any run and alignment (tests/column_sums_rows_test.cpp).
#pragma once

#include "algo/image.hpp"
#include "algo/kernel_path.hpp"

#include <array>
#include <cstdint>

namespace depthkey {

// The guided filter's moments of a guide I and a matte p (8-bit): sums of
// I, p, I^2 and I p, in that order.
using MomentSums = std::array<uint32_t *, 4>;
void stepMomentColumnsRow_C(const uint8_t *iIn, const uint8_t *pIn, const uint8_t *iOut, const uint8_t *pOut, int n,
			    const MomentSums &sums);
void stepMomentColumnsRow_SSE2(const uint8_t *iIn, const uint8_t *pIn, const uint8_t *iOut, const uint8_t *pOut,
			       int n, const MomentSums &sums);
void stepMomentColumnsRow_NEON(const uint8_t *iIn, const uint8_t *pIn, const uint8_t *iOut, const uint8_t *pOut,
			       int n, const MomentSums &sums);
using MomentColumnsFn = void (*)(const uint8_t *, const uint8_t *, const uint8_t *, const uint8_t *, int,
				 const MomentSums &);
MomentColumnsFn momentColumnsRow(KernelPath path);

// The guided filter's coefficients a and b (32-bit, summed as their bits):
// sums of a and b.
using PairSums = std::array<uint32_t *, 2>;
void stepPairColumnsRow_C(const int32_t *aIn, const int32_t *bIn, const int32_t *aOut, const int32_t *bOut, int n,
			  const PairSums &sums);
void stepPairColumnsRow_SSE2(const int32_t *aIn, const int32_t *bIn, const int32_t *aOut, const int32_t *bOut, int n,
			     const PairSums &sums);
void stepPairColumnsRow_NEON(const int32_t *aIn, const int32_t *bIn, const int32_t *aOut, const int32_t *bOut, int n,
			     const PairSums &sums);
using PairColumnsFn = void (*)(const int32_t *, const int32_t *, const int32_t *, const int32_t *, int,
			       const PairSums &);
PairColumnsFn pairColumnsRow(KernelPath path);

// The boundary unmixing's sides: of the pixels whose kind is `lecturer`
// their R, G, B and count, then of those whose kind is `board` the same.
struct SideKinds {
	uint8_t lecturer, board;
};
using SideSums = std::array<uint32_t *, 8>;
void stepSideColumnsRow_C(const uint8_t *kIn, const Rgb8 *cIn, const uint8_t *kOut, const Rgb8 *cOut, int n,
			  SideKinds kinds, const SideSums &sums);
void stepSideColumnsRow_SSE2(const uint8_t *kIn, const Rgb8 *cIn, const uint8_t *kOut, const Rgb8 *cOut, int n,
			     SideKinds kinds, const SideSums &sums);
void stepSideColumnsRow_NEON(const uint8_t *kIn, const Rgb8 *cIn, const uint8_t *kOut, const Rgb8 *cOut, int n,
			     SideKinds kinds, const SideSums &sums);
using SideColumnsFn = void (*)(const uint8_t *, const Rgb8 *, const uint8_t *, const Rgb8 *, int, SideKinds,
			       const SideSums &);
SideColumnsFn sideColumnsRow(KernelPath path);

} // namespace depthkey
