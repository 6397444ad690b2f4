// StaticBackground as it was before issue 28 (algo/static_background.hpp):
// each pixel's 3x3 box summed afresh, nine clamps a pixel. Kept as the
// reference that StaticBackground, which sums the boxes by rows, must equal
// bit for bit.
#pragma once

#include "algo/image.hpp"
#include "algo/static_background.hpp"

#include <cstdint>
#include <vector>

namespace depthkey::test {

class StaticBackgroundPerPixelBox
{
public:
	static constexpr int kToleranceMm = StaticBackground::kToleranceMm;
	static constexpr int kFadeMmPerFrame = StaticBackground::kFadeMmPerFrame;
	static constexpr int kRateShift = StaticBackground::kRateShift;
	static constexpr int kFractionBits = StaticBackground::kFractionBits;

	void update(const Gray16Image &depthMm, Gray8Image &moving);
	int meanMm(size_t i) const { return i < mean_.size() ? mean_.data()[i] >> kFractionBits : 0; }

private:
	bool inFrontPooled(int x, int y) const;

	Gray16Image mean_, deviation_;
	Gray8Image inFront_, pooled_;
	std::vector<int32_t> excess_;
};

} // namespace depthkey::test
