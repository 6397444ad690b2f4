// Binary morphology and connected components on 0 / non-zero masks (results
// are 0 / 255). Square structuring elements of (2r+1)^2 pixels, computed
// separably with running counts, so the cost does not grow with the radius.
// Outside the image the nearest edge pixel repeats: a lecturer cut by the
// frame's edge is not eroded away from it. Scratch buffers are the caller's
// and grow once; in steady state nothing allocates.
#pragma once

#include "algo/image.hpp"

#include <cstdint>
#include <vector>

namespace depthkey {

struct MorphologyScratch {
	Gray8Image pass;                 // the horizontal pass's result
	std::vector<int32_t> prefix;     // running counts of one row or column
};

void erodeSquare(const Gray8Image &in, int radius, Gray8Image &out, MorphologyScratch &scratch);
void dilateSquare(const Gray8Image &in, int radius, Gray8Image &out, MorphologyScratch &scratch);

struct ComponentScratch {
	std::vector<int32_t> labels;
	std::vector<int32_t> stack;
};

// Keeps only the largest 4-connected component of mask (in place, 0 / 255)
// and returns its size in pixels (0 when the mask is empty). Ties go to the
// component met first in raster order.
int keepLargestComponent(Gray8Image &mask, ComponentScratch &scratch);

} // namespace depthkey
