#include "algo/max_paint_rows.hpp"

#include <algorithm>

namespace depthkey {

// 16 lanes on, then 16 off: from kFirstLanesMask + 16 - n, the first n on.
alignas(16) const uint8_t kFirstLanesMask[32] = {
	0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff,
};

void maxPaintRow_C(uint8_t *row, int n, int /*room*/, uint8_t value)
{
	for (int x = 0; x < n; ++x)
		row[x] = std::max(row[x], value);
}

MaxPaintFn maxPaintRow(KernelPath path)
{
	if (sse2Rows(path))
		return maxPaintRow_SSE2;
	if (path == KernelPath::Neon)
		return maxPaintRow_NEON;
	return maxPaintRow_C;
}

} // namespace depthkey
