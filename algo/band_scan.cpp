#include "algo/band_scan.hpp"

namespace depthkey {

int nextUndecidedRow_C(const uint8_t *labels, int x, int end)
{
	while (x < end && isTrimapSeed(labels[x]))
		++x;
	return x;
}

BandScanFn bandScanRow(KernelPath path)
{
	if (sse2Rows(path))
		return nextUndecidedRow_SSE2;
	if (path == KernelPath::Neon)
		return nextUndecidedRow_NEON;
	return nextUndecidedRow_C;
}

} // namespace depthkey
