#include "algo/edge_kinds_rows.hpp"

namespace depthkey {

void edgeKindsRow_C(const uint8_t *up, const uint8_t *m, const uint8_t *down, int n, uint8_t *kinds)
{
	for (int x = 0; x < n; ++x)
		kinds[x] = edgeKindOf(m[x] + m[x - 1] + m[x + 1] + up[x] + down[x], m[x]);
}

EdgeKindsFn edgeKindsRow(KernelPath path)
{
	return sse2Rows(path) ? edgeKindsRow_SSE2 : path == KernelPath::Neon ? edgeKindsRow_NEON : edgeKindsRow_C;
}

} // namespace depthkey
