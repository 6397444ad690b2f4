#include "algo/board_learn_rows.hpp"

#include "algo/board_model.hpp"
#include "algo/trimap.hpp"

namespace depthkey {

void boardLearnRow_C(const Rgb8 *colour, const uint8_t *trimap, Rgba8 *model, int n, BoardTeachSums &sums)
{
	for (int x = 0; x < n; ++x) {
		if (trimap[x] != kTrimapBoard)
			continue;
		Rgba8 &m = model[x];
		if (m.a) {
			sums.predicted[0] += colour[x].r;
			sums.predicted[1] += colour[x].g;
			sums.predicted[2] += colour[x].b;
			sums.model[0] += m.r;
			sums.model[1] += m.g;
			sums.model[2] += m.b;
		}
		BoardModel::update(m, colour[x]);
	}
}

void boardAlphaOrRow_C(const uint8_t *a, const uint8_t *b, const uint8_t *c, uint8_t *out, int n)
{
	for (int x = 0; x < n; ++x)
		out[x] = uint8_t(a[x] | b[x] | c[x]);
}

void boardDecidedSelectRow_C(const uint8_t *near, const uint8_t *trimap, int margin, uint8_t *select, int n)
{
	for (int x = 0; x < n; ++x) {
		const bool decided = trimap[x] != kTrimapBoard && trimap[x] != kTrimapLecturer;
		const bool clear = (near[x - margin] | near[x] | near[x + margin]) == 0;
		select[x] = decided && clear ? kTrimapBoard : kTrimapLecturer;
	}
}

BoardLearnRows boardLearnRows(KernelPath path)
{
#if defined(__SSE2__)
	if (sse2Rows(path))
		return { boardLearnRow_SSE2, boardAlphaOrRow_SSE2, boardDecidedSelectRow_SSE2 };
#elif defined(__ARM_NEON)
	if (path == KernelPath::Neon)
		return { boardLearnRow_NEON, boardAlphaOrRow_NEON, boardDecidedSelectRow_NEON };
#else
	(void)path;
#endif
	return { boardLearnRow_C, boardAlphaOrRow_C, boardDecidedSelectRow_C };
}

} // namespace depthkey
