#include "algo/column_sums_rows.hpp"

namespace depthkey {

void stepMomentColumnsRow_C(const uint8_t *iIn, const uint8_t *pIn, const uint8_t *iOut, const uint8_t *pOut, int n,
			    const MomentSums &sums)
{
	for (int x = 0; x < n; ++x) {
		const uint32_t i = iIn[x], p = pIn[x], io = iOut[x], po = pOut[x];
		sums[0][x] += i - io;
		sums[1][x] += p - po;
		sums[2][x] += i * i - io * io;
		sums[3][x] += i * p - io * po;
	}
}

void stepPairColumnsRow_C(const int32_t *aIn, const int32_t *bIn, const int32_t *aOut, const int32_t *bOut, int n,
			  const PairSums &sums)
{
	for (int x = 0; x < n; ++x) {
		sums[0][x] += uint32_t(aIn[x]) - uint32_t(aOut[x]);
		sums[1][x] += uint32_t(bIn[x]) - uint32_t(bOut[x]);
	}
}

void stepSideColumnsRow_C(const uint8_t *kIn, const Rgb8 *cIn, const uint8_t *kOut, const Rgb8 *cOut, int n,
			  SideKinds kinds, const SideSums &sums)
{
	for (int x = 0; x < n; ++x) {
		const uint32_t lIn = kIn[x] == kinds.lecturer, bIn = kIn[x] == kinds.board;
		const uint32_t lOut = kOut[x] == kinds.lecturer, bOut = kOut[x] == kinds.board;
		const Rgb8 in = cIn[x], out = cOut[x];
		sums[0][x] += lIn * in.r - lOut * out.r;
		sums[1][x] += lIn * in.g - lOut * out.g;
		sums[2][x] += lIn * in.b - lOut * out.b;
		sums[3][x] += lIn - lOut;
		sums[4][x] += bIn * in.r - bOut * out.r;
		sums[5][x] += bIn * in.g - bOut * out.g;
		sums[6][x] += bIn * in.b - bOut * out.b;
		sums[7][x] += bIn - bOut;
	}
}

MomentColumnsFn momentColumnsRow(KernelPath path)
{
	return sse2Rows(path) ? stepMomentColumnsRow_SSE2
	       : path == KernelPath::Neon ? stepMomentColumnsRow_NEON
					  : stepMomentColumnsRow_C;
}

PairColumnsFn pairColumnsRow(KernelPath path)
{
	return sse2Rows(path) ? stepPairColumnsRow_SSE2 : path == KernelPath::Neon ? stepPairColumnsRow_NEON : stepPairColumnsRow_C;
}

SideColumnsFn sideColumnsRow(KernelPath path)
{
	return sse2Rows(path) ? stepSideColumnsRow_SSE2 : path == KernelPath::Neon ? stepSideColumnsRow_NEON : stepSideColumnsRow_C;
}

} // namespace depthkey
