// The boundary unmixing as it was before issue 28 (algo/boundary_unmixing.hpp):
// every pass finds every ROI pixel's kind and sums each looked-at pixel's
// 7x7 window pixel by pixel. Kept as the reference that BoundaryUnmixing,
// which works only along the edge, must equal bit for bit.
#pragma once

#include "algo/board_model.hpp"
#include "algo/image.hpp"
#include "algo/trimap.hpp"

namespace depthkey::test {

class BoundaryUnmixingWholeRoi
{
public:
	static constexpr int kWindowRadius = 3; // F and the local B from within 3 px
	static constexpr int kPasses = 3;       // BF 2: 0.872, 3: 0.873, 5: 0.873 (IoU 0.961, 0.961, 0.961)

	// minContrast2: the least |F - B|^2 (squared 8-bit levels, summed over
	// R, G and B) for the projection to decide; 0 = off.
	void configure(int minContrast2) { minContrast2_ = minContrast2; }

	// matte: 0 or 255 inside roi (board outside). Board pixels along its
	// edge that the trimap leaves undecided (outside the superset stays
	// board) become lecturer where they unmix to him, kPasses times.
	// Returns how many pixels changed.
	int refine(const RgbImage &colour, const Gray8Image &trimap, const BoardModel &board, const Roi &roi,
		   Gray8Image &matte);

private:
	// What a pixel is before a pass: inside one side (all 4-neighbours
	// alike), or on the edge, and on which side.
	enum Kind : uint8_t { kBoardEdge = 0, kLecturerEdge = 1, kLecturerInside = 2, kBoardInside = 3 };
	int pass(const RgbImage &colour, const Gray8Image &trimap, const BoardModel &board, const Roi &roi,
		 Gray8Image &matte);

	int minContrast2_ = 0;
	Gray8Image kind_;
};

} // namespace depthkey::test
