#include "algo/luma_rows.hpp"

namespace depthkey {

void lumaRow_C(const Rgb8 *colour, int n, uint8_t *luma)
{
	for (int x = 0; x < n; ++x)
		luma[x] = uint8_t((colour[x].r + 2 * colour[x].g + colour[x].b + 2) >> 2);
}

LumaFn lumaRow(KernelPath path)
{
	return sse2Rows(path) ? lumaRow_SSE2 : path == KernelPath::Neon ? lumaRow_NEON : lumaRow_C;
}

} // namespace depthkey
