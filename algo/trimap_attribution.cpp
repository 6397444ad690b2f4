#include "algo/trimap_attribution.hpp"

#include "algo/trimap.hpp"

namespace depthkey {

void TrimapAttribution::add(const Gray8Image &alpha, const Gray8Image &truth, const Gray8Image &trimap,
			    SegmentationScorer &scorer)
{
	if (trimap.size() != truth.size() || alpha.size() != truth.size() || truth.empty())
		return;
	perfectBand_.resize(alpha.width(), alpha.height());
	for (size_t i = 0; i < truth.size(); ++i) {
		const bool said = alpha.data()[i] >= 128, is = truth.data()[i] >= 128;
		const uint8_t t = trimap.data()[i];
		const Region r = t == kTrimapLecturer ? SurelyLecturer : t == kTrimapBoard ? SurelyBoard : Band;
		pixels_[r]++;
		wrong_[r] += said != is;
		bandTaken_ += r == Band && said && !is;
		perfectBand_.data()[i] = r == Band ? truth.data()[i] : alpha.data()[i];
	}
	bound_.add(scorer.score(perfectBand_, truth));
}

} // namespace depthkey
