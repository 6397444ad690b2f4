#include "algo/board_teach_rows.hpp"

#include "algo/board_model.hpp"
#include "algo/trimap.hpp"

namespace depthkey {

void boardTeachRow_C(const Rgb8 *sampled, const uint8_t *mask, const int gainQ8[3], Rgba8 *model, int n,
		     BoardTeachSums &sums)
{
	for (int x = 0; x < n; ++x) {
		if (mask[x] != kTrimapBoard)
			continue;
		const Rgb8 p = BoardModel::scaleQ8(sampled[x], gainQ8);
		Rgba8 &m = model[x];
		if (m.a) {
			sums.predicted[0] += p.r;
			sums.predicted[1] += p.g;
			sums.predicted[2] += p.b;
			sums.model[0] += m.r;
			sums.model[1] += m.g;
			sums.model[2] += m.b;
		}
		BoardModel::update(m, p);
	}
}

BoardTeachRowFn boardTeachRow(KernelPath path, const int gainQ8[3])
{
	for (int k = 0; k < 3; ++k)
		if (gainQ8[k] < 0 || gainQ8[k] > 32767)
			return boardTeachRow_C;
	if ((path == KernelPath::Ssse3 || path == KernelPath::Avx2) && cpuHasSsse3())
		return boardTeachRow_SSSE3;
	return sse2Rows(path) ? boardTeachRow_SSE2 : path == KernelPath::Neon ? boardTeachRow_NEON : boardTeachRow_C;
}

} // namespace depthkey
