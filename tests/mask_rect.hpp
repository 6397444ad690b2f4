// A 0/255 mask with one filled rectangle: the shapes the scorer tests
// (segmentation_metrics_test, live_score_test) score.
#pragma once

#include "algo/image.hpp"

namespace depthkey::test {

inline Gray8Image maskRect(int w, int h, int x0, int y0, int x1, int y1) // [x0, x1) x [y0, y1)
{
	Gray8Image m(w, h, 0);
	for (int y = y0; y < y1; ++y)
		for (int x = x0; x < x1; ++x)
			m.at(x, y) = 255;
	return m;
}

} // namespace depthkey::test
