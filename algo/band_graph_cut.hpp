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
// The max-flow is OpenCV's (cv::detail::GCGraph, the Boykov-Kolmogorov
// algorithm grabCut uses), in 32-bit integers where the flow cannot overflow
// them, else 64-bit. It has no reset, so its graph is made anew each frame:
// the one stage that allocates per frame (a handful of blocks, sized by the
// band; tests/pipeline_test.cpp bounds them). Keeping the graph between
// frames (emptied by assigning an empty one, which keeps the vectors'
// capacity) was tried: maxFlow() still grows its own list of orphans each
// frame (2-6 blocks), the page faults a frame stayed the same (57 and 54 in
// BM_PipelineFrameLecture at 640x480 with the daemon's 128 KiB mmap
// threshold: the kernel backs the graph with huge pages), no time gain
// showed in the noise, and the graph's 5-6 MB would stay resident.
#pragma once

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

class BandGraphCut
{
public:
	// smoothness 0 turns the cut off; edgeSigma in 8-bit levels (RGB).
	void configure(int smoothness, int edgeSigma);
	bool enabled() const { return smoothness_ > 0; }

	// Decides every band pixel: decisions[k] = 255 (lecturer) or 0 for the
	// band pixel k of spans (row-major, as SioxRefiner collects them).
	// trimap tells the fixed neighbours: kTrimapLecturer and kTrimapBoard.
	void cut(const RgbImage &colour, const Gray8Image &trimap, const std::vector<BandSpan> &spans,
		 const uint8_t *confidence, uint8_t *decisions);

	// The weight of cutting between two colours (for tests).
	int edgeWeight(Rgb8 a, Rgb8 b) const;

private:
	template<typename Weight>
	void cutWith(const RgbImage &colour, const Gray8Image &trimap, const std::vector<BandSpan> &spans, int pixels,
		     const uint8_t *confidence, uint8_t *decisions);

	int smoothness_ = 0;
	// smoothness * exp(-d2 / (2 sigma^2)) by squared RGB distance d2, up to
	// where it rounds to 0.
	std::vector<int> weightByDistance2_;
	std::vector<int> rowFirstSpan_; // per row + 1: index of its first span
	std::vector<int> terminal_;     // per band pixel: toLecturer - toBoard
};

} // namespace depthkey
