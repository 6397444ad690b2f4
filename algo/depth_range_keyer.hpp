// The skeleton's segmentation (the paper's Figure 4 baseline without
// calibration): a colour pixel is lecturer when the depth of the ToF pixel
// nearest to it lies in [near, far]. The real pipeline replaces it; it stays
// as the "depth-only" reference the pipeline is measured against.
#pragma once

#include "algo/image.hpp"

#include <vector>

namespace depthkey {

class DepthRangeKeyer
{
public:
	// Precomputes which depth pixel each colour pixel reads, so that the per
	// frame work is two table lookups and a compare per pixel.
	void configure(int colourWidth, int colourHeight, int depthWidth, int depthHeight);

	// alpha is resized to the colour size; 255 = lecturer, 0 = board.
	void key(const Gray16Image &depthMm, int nearMm, int farMm, Gray8Image &alpha) const;

private:
	int colourWidth_ = 0, colourHeight_ = 0, depthWidth_ = 0, depthHeight_ = 0;
	std::vector<int> sourceColumn_;
	std::vector<int> sourceRow_;
};

} // namespace depthkey
