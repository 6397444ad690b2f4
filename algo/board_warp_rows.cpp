#include "algo/board_warp_rows.hpp"

namespace depthkey {

void boardWarpRow_C(const BoardWarpRow &r, int opacityQ8)
{
	for (int x = 0; x < r.count; ++x)
		boardWarpPixel_C(r, x, opacityQ8);
}

BoardWarpRowFn boardWarpRowFn(KernelPath path)
{
	if (path == KernelPath::Avx2 && cpuHasAvx2())
		return boardWarpRow_AVX2;
	if ((path == KernelPath::Ssse3 || path == KernelPath::Avx2) && cpuHasSsse3())
		return boardWarpRow_SSSE3;
	if (sse2Rows(path))
		return boardWarpRow_SSE2;
	if (path == KernelPath::Neon)
		return boardWarpRow_NEON;
	return boardWarpRow_C;
}

void boardWarpRow(KernelPath path, const BoardWarpRow &row, int opacityQ8)
{
	boardWarpRowFn(path)(row, opacityQ8);
}

} // namespace depthkey
