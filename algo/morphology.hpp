// Binary morphology and connected components on 0 / non-zero masks (results
// are 0 / 255). Square structuring elements of (2r+1)^2 pixels, computed
// separably: a row is the OR (dilate) or AND (erode) of 2r+1 shifted copies
// of the padded input row, a column pass the same over 2r+1 whole rows, 16
// pixels per SSE2 instruction (algo/mask_rows.hpp).
// Outside the image the nearest edge pixel repeats: a lecturer cut by the
// frame's edge is not eroded away from it. Scratch buffers are the caller's
// and grow once; in steady state nothing allocates.
#pragma once

#include "algo/image.hpp"
#include "algo/kernel_path.hpp"

#include <cstdint>
#include <vector>

namespace depthkey {

struct MorphologyScratch {
	Gray8Image pass;                 // the horizontal pass's result
	std::vector<uint8_t> padded;     // one input row, edge pixels repeated r times
};

void erodeSquare(const Gray8Image &in, int radius, Gray8Image &out, MorphologyScratch &scratch,
		 KernelPath path = bestKernelPath());
void dilateSquare(const Gray8Image &in, int radius, Gray8Image &out, MorphologyScratch &scratch,
		  KernelPath path = bestKernelPath());

struct ComponentScratch {
	std::vector<int32_t> labels;   // (w+2) x (h+2), see labelComponents
	std::vector<int32_t> stack;
	std::vector<int32_t> sizes;    // pixels per component
	std::vector<int32_t> counts;   // per component, for the caller's statistics
};

constexpr int32_t kNoComponent = -2;

// Labels the 4-connected components of mask 0, 1, ... in raster order of
// their first pixel: scratch.labels holds pixel (x, y)'s label at
// (y + 1) * (w + 2) + x + 1 (kNoComponent outside the mask and on the
// one-pixel frame), scratch.sizes each component's size. Returns how many.
int labelComponents(const Gray8Image &mask, ComponentScratch &scratch);
// Keeps only the component `label` of the last labelComponents (255), the
// rest 0; label < 0 clears the mask.
void keepComponent(Gray8Image &mask, const ComponentScratch &scratch, int label);

// Keeps the 4-connected components of mask that hold a non-zero pixel of
// seeds (same size; morphological reconstruction), in place, and returns
// their size in pixels.
int keepComponentsTouching(Gray8Image &mask, const Gray8Image &seeds, ComponentScratch &scratch);

} // namespace depthkey
