// The fixed-point depth -> colour mapping (algo/depth_mapper.hpp) against
// MappingModel's floating-point map, for both calibrated models.
#include "algo/depth_mapper.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

using namespace depthkey;

TEST(DepthMapper, FixedPointWithinHalfAPixelOfTheModel)
{
	// A paper model and a parallax model with coefficients of the size a
	// calibration gives (tens of pixels of parallax at 1 m).
	for (MappingKind kind : { MappingKind::Paper, MappingKind::Parallax }) {
		MappingModel model;
		model.kind = kind;
		model.colourWidth = 1920;
		model.colourHeight = 1080;
		if (kind == MappingKind::Paper) {
			model.x = { 960, 1000, 5, -30, 12 };
			model.y = { 540, 560, -4, 20, -8 };
		} else {
			model.x = { 940, 1010, 8, 3, -6, 2, -35, 4, -3, 1, 40, -3, 2, 6 };
			model.y = { 530, 5, 570, -2, 4, 3, 2, -28, 3, 1, -6, 1, -2, -3 };
		}
		DepthMapper mapper;
		mapper.configure(model);
		double worst = 0;
		for (int v = 0; v < model.tofHeight; v += 3)
			for (int u = 0; u < model.tofWidth; u += 3)
				for (int z = 400; z <= 7500; z += 137) {
					double x, y;
					model.map(u, v, z / 1000.0, x, y);
					int32_t xq, yq;
					mapper.map(v * model.tofWidth + u, z, xq, yq);
					worst = std::max({ worst, std::fabs(xq / 256.0 - x), std::fabs(yq / 256.0 - y) });
				}
		std::printf("mapping %s: max |fixed - model| = %.5f px\n", mappingKindName(kind), worst);
		EXPECT_LE(worst, 0.5);
		EXPECT_LE(worst, 0.01); // in fact: Q8 rounding
	}
}
