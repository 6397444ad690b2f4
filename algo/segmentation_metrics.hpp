// How good a segmentation is against the truth, per frame: the numbers
// depthkey-eval reports. A pixel is lecturer when its value is >= 128 (an
// alpha matte and a 0/255 mask both work).
//   IoU        |P and T| / |P or T|                     (1 when both are empty)
//   FNR        lecturer pixels lost: |T \ P| / |T|      (0 when T is empty)
//   FPR        board taken as lecturer: |P \ T| / |not T|
//   boundary F the F-measure of boundary pixels matched within a tolerance
//              (Euclidean, 2 px by default): precision = share of P's
//              boundary near T's, recall = share of T's near P's. A boundary
//              pixel is a mask pixel with a 4-neighbour outside the mask; the
//              image border is no boundary.
#pragma once

#include "algo/image.hpp"

#include <utility>
#include <vector>

namespace depthkey {

struct SegmentationScore {
	double iou = 0, fnr = 0, fpr = 0;
	double boundaryPrecision = 0, boundaryRecall = 0, boundaryF = 0;
};

class SegmentationScorer
{
public:
	explicit SegmentationScorer(int tolerancePx = 2);

	// Sizes must match; a mismatch scores 0 everywhere (fnr, fpr 1).
	SegmentationScore score(const Gray8Image &predicted, const Gray8Image &truth);

private:
	void boundary(const Gray8Image &mask, Gray8Image &out);
	// Boundary pixels of `from` with a boundary pixel of `to` within the
	// tolerance, and how many boundary pixels `from` has.
	std::pair<long, long> matched(const Gray8Image &from, const Gray8Image &to) const;

	std::vector<std::pair<int, int>> disc_;
	Gray8Image predictedEdge_, truthEdge_;
	std::vector<uint8_t> allInside_; // the row beyond the top and bottom border
};

// Mean of per-frame scores (every frame weighs the same).
class ScoreAverage
{
public:
	void add(const SegmentationScore &s);
	SegmentationScore mean() const;
	long frames() const { return frames_; }

private:
	SegmentationScore sum_;
	long frames_ = 0;
};

} // namespace depthkey
