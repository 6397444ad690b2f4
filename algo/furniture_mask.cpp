#include "algo/furniture_mask.hpp"

#include <algorithm>

namespace depthkey {

void FurnitureMask::update(const Gray8Image &inRange, const Gray8Image &moving, const Gray8Image &previousLecturer)
{
	const int w = inRange.width(), h = inRange.height();
	if (stillFrames_.width() != w || stillFrames_.height() != h)
		stillFrames_ = Gray8Image(w, h, 0);
	if (moving.width() != w || moving.height() != h)
		return;
	const bool previous = previousLecturer.width() == w && previousLecturer.height() == h;
	const uint8_t *in = inRange.data(), *mov = moving.data();
	const uint8_t *lecturer = previous ? previousLecturer.data() : nullptr;
	uint8_t *count = stillFrames_.data();
	for (size_t i = 0; i < inRange.size(); ++i) {
		if (mov[i] || !in[i])
			count[i] = 0;
		else if (!(lecturer && lecturer[i]) && count[i] < kFramesToLearn)
			++count[i];
	}
}

void FurnitureMask::fill(Gray8Image &image, uint8_t value) const
{
	if (image.width() != stillFrames_.width() || image.height() != stillFrames_.height())
		return;
	const uint8_t *count = stillFrames_.data();
	uint8_t *m = image.data();
	for (size_t i = 0; i < image.size(); ++i)
		if (count[i] >= kFramesToLearn && m[i])
			m[i] = value;
}

} // namespace depthkey
