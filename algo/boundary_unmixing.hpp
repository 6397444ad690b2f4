// Re-decides the pixels along the decision's edge by unmixing their colour
// between the lecturer's and the board's (issue 11: the edge's last pixels).
//
// A pixel on the lecturer's silhouette is a mix: I = a F + (1 - a) B, with F
// his colour there and B the board's. Where both are dull and close (a dark
// sleeve on the dark board, some 10-15 levels apart) the cut's edge wanders
// a pixel or two off the silhouette. But B is known at every pixel the board
// was seen (the board model, algo/board_model.hpp: the board's own colour
// there, after the room light's gain; else the mean of the board pixels
// nearby), and F is the mean colour of the lecturer's interior pixels
// nearby. The coverage is the projection of I - B on F - B:
//   a = (I - B) . (F - B) / |F - B|^2,
// and the pixel is more lecturer than board iff a >= 1/2, i.e.
// 2 (I - B).(F - B) >= |F - B|^2:
// integers, no division. Where F and B are too alike (|F - B|^2 below
// minContrast2) the projection is noise and the decision stays.
//
// Only board pixels with a lecturer 4-neighbour are looked at, and only
// turned to lecturer: the edge grows outwards where the colour says the
// pixel is more him than board, never inwards. Both ways lost IoU (mean of
// seeds 1-3: 0.9593 against 0.9610 outwards only): a limb darkens towards
// its silhouette (shading), so F from his interior is too bright there and
// his true edge pixels would be unmixed to board. The cut's edge lies
// inside him on dull sleeves (60 % of the lecturer pixels lost on seed 3
// were within one pixel of his silhouette, their true coverage above one
// half); a pass moves it by one pixel at most, and kPasses passes let it
// travel. Pixels outside the superset stay board. Measured on the
// simulated lecture (seeds 1-3, all artefacts): mean IoU / BF 0.9597 /
// 0.8667 -> 0.9610 / 0.8730 at minContrast2 = 100; B from the local board
// mean alone scored lower (BF 0.870). Pure, integer, allocation-free once
// sized; tests compare it with a double reference.
//
// The work follows the edge (issue 28; the output unchanged bit for bit):
// the pixels' kinds are found over the ROI once, and after each pass again
// only around the pixels it turned; the window sums come from column sums
// kept only for the columns within kWindowRadius of a pixel looked at,
// slid along runs of them (algo/column_sums.hpp).
#pragma once

#include "algo/board_model.hpp"
#include "algo/column_sums_rows.hpp"
#include "algo/edge_kinds_rows.hpp"
#include "algo/image.hpp"
#include "algo/trimap.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace depthkey {

class BoundaryUnmixing
{
public:
	static constexpr int kWindowRadius = 3; // F and the local B from within 3 px
	static constexpr int kPasses = 3;       // BF 2: 0.872, 3: 0.873, 5: 0.873 (IoU 0.961, 0.961, 0.961)

	// minContrast2: the least |F - B|^2 (squared 8-bit levels, summed over
	// R, G and B) for the projection to decide; 0 = off.
	void configure(int minContrast2) { minContrast2_ = minContrast2; }
	// The column sums' row kernel (algo/column_sums_rows.hpp); the output
	// is the same on every path.
	void setKernelPath(KernelPath path)
	{
		sideColumns_ = sideColumnsRow(path);
		edgeKinds_ = edgeKindsRow(path);
	}

	// matte: 0 or 255 inside roi (board outside). Board pixels along its
	// edge that the trimap leaves undecided (outside the superset stays
	// board) become lecturer where they unmix to him, kPasses times.
	// Returns how many pixels changed.
	int refine(const RgbImage &colour, const Gray8Image &trimap, const BoardModel &board, const Roi &roi,
		   Gray8Image &matte);

private:
	// What a pixel is before a pass: inside one side (all 4-neighbours
	// alike), or on the edge, and on which side; kTurned: a board edge pixel
	// this pass turned to lecturer (still neither side for this pass).
	enum Kind : uint8_t {
		kBoardEdge = 0,
		kLecturerEdge = 1,
		kLecturerInside = 2,
		kBoardInside = 3,
		kTurned = 4,
	};
	static_assert(kBoardEdge == kEdgeKindBoardEdge && kLecturerEdge == kEdgeKindLecturerEdge &&
			      kLecturerInside == kEdgeKindLecturerInside && kBoardInside == kEdgeKindBoardInside,
		      "the kinds row (algo/edge_kinds_rows.hpp) writes these");
	// A pixel's kind from the sum of its and its 4-neighbours' matte.
	static uint8_t kindOf(int around, uint8_t m) { return edgeKindOf(around, m); }
	// The same at (x, y) in roi, board beyond it.
	static uint8_t kindAt(const Gray8Image &matte, const Roi &roi, int x, int y);
	void findKinds(const Gray8Image &matte, const Roi &roi);
	// After a pass: the kinds of the turned pixels and of their neighbours.
	void updateKinds(const Gray8Image &matte, const Roi &roi);
	int pass(const RgbImage &colour, const Gray8Image &trimap, const BoardModel &board, const Roi &roi,
		 Gray8Image &matte);

	int minContrast2_ = 0;
	Gray8Image kind_;
	// Per image row, the columns [turnedX0_, turnedX1_) holding the pixels
	// the last pass turned (empty: none).
	std::vector<int> turnedX0_, turnedX1_;
	// Per ROI column, the sums of the lecturer's inside pixels' R, G, B and
	// count over the window's rows, then the board's; whose window each
	// column holds.
	std::array<std::vector<uint32_t>, 8> columns_;
	std::vector<int> columnRow_;
	// Rows of zeros (kinds of neither side, and colours): what a window
	// takes in or off beyond the ROI.
	std::vector<uint8_t> zeroKinds_;
	std::vector<Rgb8> zeroColours_;
	SideColumnsFn sideColumns_ = sideColumnsRow(bestKernelPath());
	EdgeKindsFn edgeKinds_ = edgeKindsRow(bestKernelPath());
};

} // namespace depthkey
