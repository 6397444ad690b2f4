#include "algo/board_warp_rows.hpp"

namespace depthkey {

void boardWarpRow_C(const BoardWarpRow &r, int opacityQ8)
{
	for (int x = 0; x < r.count; ++x)
		boardWarpPixel_C(r, x, opacityQ8);
}

void boardWarpRow(KernelPath path, const BoardWarpRow &row, int opacityQ8)
{
	if (path == KernelPath::Sse2)
		boardWarpRow_SSE2(row, opacityQ8);
	else if (path == KernelPath::Neon)
		boardWarpRow_NEON(row, opacityQ8);
	else
		boardWarpRow_C(row, opacityQ8);
}

} // namespace depthkey
