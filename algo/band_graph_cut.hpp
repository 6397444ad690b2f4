// The band's decision made spatially coherent by a minimum cut (issue 11
// section 4, after TofCut: Wang et al., CVPR 2010). Each band pixel's fused
// confidence (colour, board model, depth, previous frame; 1..255, lecturer
// from kConfidenceLecturer) is its data term; neighbouring pixels pay to be
// cut apart, less across a colour edge:
//   E = sum_p D_p(label) + sum_{p~q, cut} smoothness * exp(-|I_p - I_q|^2 / (2 sigma^2))
// with D = confidence - 128 for board and its negative for lecturer (4-
// neighbours, RGB distance). The core and the board outside the superset
// are fixed: a band pixel next to one is pulled to its side by the same
// edge weight. Where colour is ambiguous (a dark sleeve on the dark board),
// the cut runs along the nearest colour edge between the core and the
// superset's border instead of through the noise of the per-pixel decision.
//
// The cut is solved coarse to fine (algo/coarse_to_fine_cut.hpp): this
// file states the energy on the band's grid, that one cuts it.
#pragma once

#include "algo/coarse_to_fine_cut.hpp"
#include "algo/cut_grid.hpp"
#include "algo/image.hpp"

#include <cstdint>
#include <vector>

namespace depthkey {

// A run of band pixels [x0, x1) of row y; their confidences start at index
// `first` of the band arrays, in row-major order.
struct BandSpan {
	int y, x0, x1;
	int first;
};

class BandGraphCut : private CoarseToFineCut::DeferredLinks
{
public:
	// smoothness 0 turns the cut off; edgeSigma in 8-bit levels (RGB).
	void configure(int smoothness, int edgeSigma);
	// The coarse-to-fine solve: levels of 2x2 blocks (0 = one cut of the
	// whole band) at 640 pixels wide, plus log2(width / 640) rounded (so
	// that the coarsest cell covers about the same part of the scene at
	// every size), and the coarse cells around a coarse edge cut again.
	void setLevels(int levels, int margin)
	{
		levels_ = levels;
		solver_.configure(margin);
	}
	static int levelsForWidth(int levels, int width);
	bool enabled() const { return smoothness_ > 0; }

	// Decides every band pixel: decisions[k] = 255 (lecturer) or 0 for the
	// band pixel k of spans (row-major, as SioxRefiner collects them).
	// trimap tells the fixed neighbours: kTrimapLecturer and kTrimapBoard.
	void cut(const RgbImage &colour, const Gray8Image &trimap, const std::vector<BandSpan> &spans,
		 const uint8_t *confidence, uint8_t *decisions);

	// The weight of cutting between two colours (for tests).
	int edgeWeight(Rgb8 a, Rgb8 b) const;

private:
	// The band's energy on the grid of the spans' bounding box; the links
	// between free pixels of one 2x2 block are left for weigh(): the
	// coarse levels do not use them, and the finest level only where it
	// cuts again (a sixth of the band at 640x480).
	void buildGrid(const RgbImage &colour, const Gray8Image &trimap, const std::vector<BandSpan> &spans,
		       const uint8_t *confidence);
	void weigh(CutGrid &fine, const int32_t *cells, int count) const override;

	int smoothness_ = 0;
	// smoothness * exp(-d2 / (2 sigma^2)) by squared RGB distance d2, up to
	// where it rounds to 0.
	std::vector<int> weightByDistance2_;
	int levels_ = 0;
	CutGrid grid_;
	int gridX0_ = 0, gridY0_ = 0;
	const RgbImage *colour_ = nullptr; // the frame being cut, for weigh()
	CoarseToFineCut solver_;
};

} // namespace depthkey
