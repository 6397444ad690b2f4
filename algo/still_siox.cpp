#include "algo/still_siox.hpp"

#include "algo/colour_learner.hpp"
#include "algo/trimap.hpp"

#include <cerrno>

namespace depthkey {

StillSiox::StillSiox() : classifier_(lab_)
{
}

int StillSiox::segment(const RgbImage &colour, const Gray8Image &trimap, Gray8Image &mask, Gray8Image &alpha)
{
	const int w = colour.width(), h = colour.height();
	if (trimap.width() != w || trimap.height() != h || w == 0 || h == 0)
		return -EINVAL;
	lecturer_.clear();
	board_.clear();
	for (size_t i = 0; i < colour.size(); ++i) {
		uint8_t t = trimap.data()[i];
		if (t == kTrimapLecturer)
			lecturer_.add(quantiseColour(colour.data()[i]));
		else if (t == kTrimapBoard)
			board_.add(quantiseColour(colour.data()[i]));
	}
	if (board_.total() == 0)
		return -ENODATA;
	deriveSignatures(lecturer_, board_, lab_, scratch_, classifier_);
	refiner_.refine(colour, trimap, Roi{ 0, 0, w, h }, classifier_, alpha);
	mask.resize(w, h);
	for (size_t i = 0; i < alpha.size(); ++i)
		mask.data()[i] = alpha.data()[i] >= kConfidenceLecturer ? 255 : 0;
	return 0;
}

} // namespace depthkey
