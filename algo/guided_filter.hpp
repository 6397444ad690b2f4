// The guided filter (He, Sun and Tang, ECCV 2010) of a matte, with the
// colour image's luma as guide, in fixed point (issue 11 section 5): in
// every (2r+1)^2 window k the output is a linear function of the guide,
// q = a_k I + b_k, fitted to the input p by least squares with a penalty
// eps on a_k:
//   a_k = cov_k(I, p) / (var_k(I) + eps),   b_k = mean_k(p) - a_k mean_k(I),
// and each pixel averages the a_k, b_k of the windows holding it. Where the
// guide has an edge the matte follows it, where the guide is flat the matte
// is smoothed: hard staircase edges from the ToF's coarse pixels become soft
// edges that lie on the colour image's.
//
// Only pixels within 2r of the matte's edge can change: where a window's p
// is constant, a = 0 and b = p exactly. So a, b and q are computed only
// within 2r of an edge (about a quarter of a lecture frame's ROI); the rest
// of the ROI is copied (issue 28: the work follows the edge, and the output
// is what the whole-ROI filter gave, bit for bit). Windows are clipped to
// the ROI (the matte is 0 outside it).
//
// Box sums slide: per column, the sums of I, p, I^2 and I p over the rows
// of the window (a row added at the bottom, one taken off the top), then
// along the row; a and b of a row go into a ring of 2r + 2 rows, whose
// column sums slide the same way for q, r rows behind. Column sums are kept
// only for the columns within r of an edge pixel of the row; a column that
// was not kept for the row above is summed afresh. Memory is a few rows
// (O(r W)), not whole-image integrals (24 bytes a pixel, 7 MB at 640x480:
// issue 15). Sums are kept modulo 2^32 (a box sum is below 2^32, so
// differences of wrapped sums are exact).
//   a in Q16 (|a| <= 255 / (2 sqrt(eps)) < 2^8), b in Q8: their box sums
//   fit 32 bits for r <= 7. a's division is 64-bit (its divisor, the
//   window's variance, is new at every pixel); b's and q's divisors are the
//   window's pixel count N times a power of two: the power of two is a
//   shift, N a multiply (algo/exact_divisor.hpp, the same quotient).
// Allocation-free once sized; tests compare it with a double reference.
#pragma once

#include "algo/column_sums_rows.hpp"
#include "algo/exact_divisor.hpp"
#include "algo/image.hpp"
#include "algo/luma_rows.hpp"
#include "algo/trimap.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace depthkey {

class GuidedFilter
{
public:
	static constexpr int kMaxRadius = 7;

	GuidedFilter();

	// radius 1..kMaxRadius, eps in squared 8-bit levels (>= 1).
	void configure(int radius, int eps);
	// The luma and column sums' row kernels (algo/luma_rows.hpp,
	// algo/column_sums_rows.hpp); the output is the same on every path.
	void setKernelPath(KernelPath path)
	{
		luma_ = lumaRow(path);
		momentColumns_ = momentColumnsRow(path);
		pairColumns_ = pairColumnsRow(path);
	}

	// matte: 0..255 inside roi, 0 outside; out receives the filtered matte
	// inside roi (resized to the image; outside roi untouched).
	void filter(const RgbImage &colour, const Gray8Image &matte, const Roi &roi, Gray8Image &out);

	// The window's coefficients for a pixel, for the double reference:
	// how many pixels changed in the last filter().
	size_t changedPixels() const { return changed_; }

private:
	int radius_ = 3, eps_ = 400;
	size_t changed_ = 0;
	// near_ = 1 within 2r of an edge of the matte, from a dilation of the
	// edge pixels along rows, then along columns.
	void markNearEdges(const Gray8Image &matte, const Roi &roi);
	// Row y of the ROI: a and b into the ring (a = 0, b = p off the edge),
	// from the moments' column sums of y's window.
	void coefficientsRow(const Gray8Image &matte, const Roi &roi, int y);
	// Row y of the ROI: q from the a and b of the windows holding it.
	void outputRow(const Gray8Image &matte, const Roi &roi, int y, Gray8Image &out);

	int ringRows() const { return 2 * radius_ + 2; }

	static constexpr int kMaxWindowPixels = (2 * kMaxRadius + 1) * (2 * kMaxRadius + 1);
	// byCount_[N] divides by a window's pixel count N (1..(2r + 1)^2).
	std::array<ExactDivisor, kMaxWindowPixels + 1> byCount_;

	Gray8Image guide_, near_;              // luma; 1 = within 2r of an edge
	// markNearEdges(): a ring of the edges' reach along rows (4r + 3 rows,
	// each padded to whole words), and per column how many of its rows
	// reach the column.
	std::vector<uint8_t> alongRows_, reach_;
	// Per ROI column, the sums over the rows of a window of I, p, I^2 and
	// I p, and of a and b; momentRow_ and ringRow_ say whose window (a row
	// of the ROI) each column holds.
	std::vector<uint32_t> colI_, colP_, colII_, colIP_, colA_, colB_;
	std::vector<int> momentRow_, ringRow_;
	std::vector<int32_t> a_, b_;            // ring of ROI rows, Q16 and Q8
	// A row of zeros of each kind: the row a window's column sums take in
	// or off where there is none (beyond the ROI).
	std::vector<uint8_t> zeroBytes_;
	std::vector<int32_t> zeroWords_;
	MomentColumnsFn momentColumns_ = momentColumnsRow(bestKernelPath());
	PairColumnsFn pairColumns_ = pairColumnsRow(bestKernelPath());
	LumaFn luma_ = lumaRow(bestKernelPath());
};

} // namespace depthkey
