// Where a segmentation's errors come from, judged against the ground truth:
// a wrong pixel the trimap called surely lecturer or surely board is the
// depth seeds' fault (the refinement never changes seeds), a wrong band
// pixel SIOX's. And the bound the seeds set: the scores the segmentation
// would get if every band pixel were decided right. For depthkey-eval; pure,
// allocates only when sizes change.
#pragma once

#include "algo/image.hpp"
#include "algo/segmentation_metrics.hpp"

#include <cstdint>

namespace depthkey {

class TrimapAttribution
{
public:
	enum Region { SurelyLecturer, Band, SurelyBoard, Regions };

	// One frame: the segmentation (>= 128 = lecturer), the truth and the
	// trimap it was refined from, all the same size (else ignored).
	void add(const Gray8Image &alpha, const Gray8Image &truth, const Gray8Image &trimap, SegmentationScorer &scorer);

	uint64_t pixels(Region r) const { return pixels_[r]; }
	uint64_t wrong(Region r) const { return wrong_[r]; }
	// Band pixels called lecturer that are board.
	uint64_t bandTaken() const { return bandTaken_; }
	// Mean scores with every band pixel set to the truth.
	SegmentationScore bound() const { return bound_.mean(); }

private:
	uint64_t pixels_[Regions] = {}, wrong_[Regions] = {}, bandTaken_ = 0;
	Gray8Image perfectBand_;
	ScoreAverage bound_;
};

} // namespace depthkey
