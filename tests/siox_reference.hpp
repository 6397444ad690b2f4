// A floating-point reference of SIOX 1.13 (Friedland, Jantz, Rojas; the
// Java SioxSegmentator / ColorSignature / Utils from siox.org, re-written
// from their documented behaviour, in double):
//   - rgbToClab: sRGB -> CIELAB (D65) by the easyrgb.com formulas;
//   - createSignature: two-stage modified k-d clustering, limits
//     0.64 / 1.28 / 2.56, clusters under 0.1 % of the samples dropped;
//   - segmentate: known pixels from the confidence matrix (<= 0.1 board,
//     >= 0.8 lecturer), the rest classified (board iff minBg < minFg),
//     smoothcm / normalise / erode / keepOnlyLargeComponents /
//     smoothness x smoothcm / normalise / threshold 0.5 /
//     keepOnlyLargeComponents / fillColorRegions / dilate.
// It is the reference the fixed-point kernels are tested against, and the
// "reference SIOX 1.13" depthkey-siox's accuracy is compared with. No SIOX
// implementation is installed on the build machine, so this is it.
#pragma once

#include "algo/image.hpp"

#include <array>
#include <vector>

namespace depthkey::test {

using LabD = std::array<double, 3>;

LabD referenceLab(Rgb8 c);

struct WeightedLabD {
	LabD lab;
	double weight = 1.0;
};

// Signature centroids (stage two), in the order the recursion emits them.
// roundStageOne rounds the stage-one centroids to integers, as the fixed-point
// kernel (integer Lab16) must: with it the two agree exactly.
std::vector<WeightedLabD> referenceSignature(std::vector<WeightedLabD> points,
					     const LabD &limits = { 0.64, 1.28, 2.56 },
					     bool roundStageOne = false);

double referenceNearest(const std::vector<WeightedLabD> &signature, const LabD &c);

struct ReferenceSioxOptions {
	int smoothness = 1;
	double sizeFactorToKeep = 0.0; // 0: keep components holding known lecturer pixels
};

// trimap: 0 board, 255 lecturer, else undecided. Returns the mask (0/255).
Gray8Image referenceSegmentate(const RgbImage &image, const Gray8Image &trimap,
			       const ReferenceSioxOptions &options = {});

} // namespace depthkey::test
