// The guided filter as it was before issue 28 (algo/guided_filter.hpp): the
// moments' column sums and the windows slid across the whole ROI, the
// pixels near an edge marked square by square. Kept as the reference that
// GuidedFilter, which works only near the edge, must equal bit for bit.
#pragma once

#include "algo/image.hpp"
#include "algo/trimap.hpp"

#include <cstdint>
#include <vector>

namespace depthkey::test {

class GuidedFilterWholeRoi
{
public:
	static constexpr int kMaxRadius = 7;

	// radius 1..kMaxRadius, eps in squared 8-bit levels (>= 1).
	void configure(int radius, int eps);

	// matte: 0..255 inside roi, 0 outside; out receives the filtered matte
	// inside roi (resized to the image; outside roi untouched).
	void filter(const RgbImage &colour, const Gray8Image &matte, const Roi &roi, Gray8Image &out);

	// How many pixels changed in the last filter().
	size_t changedPixels() const { return changed_; }

private:
	int radius_ = 3, eps_ = 400;
	size_t changed_ = 0;
	void markNearEdges(const Gray8Image &matte, const Roi &roi);
	// Row y of the ROI: the moments' column sums from the rows of y's
	// window, then a and b into the ring.
	void coefficientsRow(const Gray8Image &matte, const Roi &roi, int y);
	// Row y of the ROI: q from the a and b of the windows holding it.
	void outputRow(const Gray8Image &matte, const Roi &roi, int y, Gray8Image &out);

	int ringRows() const { return 2 * radius_ + 2; }

	Gray8Image guide_, near_;              // luma; 1 = within 2r of an edge
	// Per ROI column, the sums over the rows [momentTop_, momentEnd_) of
	// I, p, I^2 and I p, and over [ringTop_, ringEnd_) of a and b.
	std::vector<uint32_t> colI_, colP_, colII_, colIP_, colA_, colB_;
	int momentTop_ = 0, momentEnd_ = 0, ringTop_ = 0, ringEnd_ = 0;
	std::vector<int32_t> a_, b_;            // ring of ROI rows, Q16 and Q8
};

} // namespace depthkey::test
