#include "algo/seed_mapper.hpp"

#include <algorithm>
#include <cstring>

namespace depthkey {

void SeedMapper::configure(const DepthMapper &mapper)
{
	mapper_ = &mapper;
	// ceil(colour / tof) + 1 pixel of overlap.
	footprintW_ = (mapper.colourWidth() + mapper.tofWidth() - 1) / std::max(1, mapper.tofWidth()) + 1;
	footprintH_ = (mapper.colourHeight() + mapper.tofHeight() - 1) / std::max(1, mapper.tofHeight()) + 1;
	previous_ = {};
}

void SeedMapper::map(const DepthSeeds &seeds, const Gray16Image &depthMm, Gray8Image &trimap, Roi &roi)
{
	const int cw = mapper_->colourWidth(), ch = mapper_->colourHeight();
	const int tw = mapper_->tofWidth(), th = mapper_->tofHeight();
	if (trimap.width() != cw || trimap.height() != ch) {
		trimap.resize(cw, ch);
		std::memset(trimap.data(), kTrimapBoard, trimap.size());
		previous_ = {};
	}
	for (int y = previous_.y0; y < previous_.y1; ++y)
		std::memset(trimap.row(y) + previous_.x0, kTrimapBoard, size_t(previous_.x1 - previous_.x0));

	roi = { cw, ch, 0, 0 };
	bool sizesMatch = seeds.labels.width() == tw && seeds.labels.height() == th &&
			  depthMm.width() == tw && depthMm.height() == th;
	if (!sizesMatch || seeds.lecturerPixels == 0) {
		roi = {};
		previous_ = roi;
		return;
	}
	const int halfW = footprintW_ * 128, halfH = footprintH_ * 128; // footprint / 2 in Q8
	const uint8_t *labels = seeds.labels.data();
	const uint16_t *depth = depthMm.data();
	for (int i = 0; i < tw * th; ++i) {
		uint8_t label = labels[i];
		if (label == kTrimapBoard)
			continue;
		// No measurement (0): assume the lecturer's depth, the likeliest
		// surface next to the lecturer's seeds.
		int z = depth[i] ? depth[i] : seeds.lecturerDepthMm;
		int32_t xQ8, yQ8;
		mapper_->map(i, z, xQ8, yQ8);
		int x0 = std::max(0, (xQ8 - halfW + 128) >> 8), y0 = std::max(0, (yQ8 - halfH + 128) >> 8);
		int x1 = std::min(cw, ((xQ8 - halfW + 128) >> 8) + footprintW_);
		int y1 = std::min(ch, ((yQ8 - halfH + 128) >> 8) + footprintH_);
		if (x0 >= x1 || y0 >= y1)
			continue;
		for (int y = y0; y < y1; ++y) {
			uint8_t *row = trimap.row(y);
			for (int x = x0; x < x1; ++x)
				row[x] = std::max(row[x], label);
		}
		roi.x0 = std::min(roi.x0, x0);
		roi.y0 = std::min(roi.y0, y0);
		roi.x1 = std::max(roi.x1, x1);
		roi.y1 = std::max(roi.y1, y1);
	}
	if (roi.empty()) {
		roi = {};
	} else {
		// One pixel of board around the painted region, so neighbours of
		// every ROI pixel are inside the ROI or the image border.
		roi = { std::max(0, roi.x0 - 1), std::max(0, roi.y0 - 1), std::min(cw, roi.x1 + 1),
			std::min(ch, roi.y1 + 1) };
	}
	previous_ = roi;
}

} // namespace depthkey
