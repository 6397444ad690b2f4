#include "algo/depth_range_keyer.hpp"

namespace depthkey {

void DepthRangeKeyer::configure(int colourWidth, int colourHeight, int depthWidth, int depthHeight)
{
	colourWidth_ = colourWidth;
	colourHeight_ = colourHeight;
	depthWidth_ = depthWidth;
	depthHeight_ = depthHeight;
	sourceColumn_.resize(colourWidth);
	sourceRow_.resize(colourHeight);
	// Pixel centres map onto pixel centres: src = (dst + 0.5) * srcSize / dstSize,
	// in integers: (2 * dst + 1) * srcSize / (2 * dstSize).
	for (int x = 0; x < colourWidth; ++x)
		sourceColumn_[x] = (2 * x + 1) * depthWidth / (2 * colourWidth);
	for (int y = 0; y < colourHeight; ++y)
		sourceRow_[y] = (2 * y + 1) * depthHeight / (2 * colourHeight);
}

void DepthRangeKeyer::key(const Gray16Image &depthMm, int nearMm, int farMm, Gray8Image &alpha) const
{
	alpha.resize(colourWidth_, colourHeight_);
	if (depthMm.width() != depthWidth_ || depthMm.height() != depthHeight_) {
		// A frame of another size than configured is not used (all board).
		for (size_t i = 0; i < alpha.size(); ++i)
			alpha.data()[i] = 0;
		return;
	}
	const unsigned nearU = static_cast<unsigned>(nearMm);
	const unsigned spanU = static_cast<unsigned>(farMm - nearMm);
	for (int y = 0; y < colourHeight_; ++y) {
		const uint16_t *src = depthMm.row(sourceRow_[y]);
		uint8_t *dst = alpha.row(y);
		for (int x = 0; x < colourWidth_; ++x) {
			// One unsigned compare tests near <= d <= far (0 = no data is out).
			unsigned d = src[sourceColumn_[x]];
			dst[x] = (d - nearU <= spanU) ? 255 : 0;
		}
	}
}

} // namespace depthkey
