// The pre-issue-28 boundary unmixing, unchanged but for its name (see the header).
#include "tests/boundary_unmixing_whole_roi.hpp"

#include <algorithm>

namespace depthkey::test {

namespace {

// The matte at (x, y): 0 outside roi (board there).
inline uint8_t at(const Gray8Image &m, const Roi &roi, int x, int y)
{
	return (x < roi.x0 || x >= roi.x1 || y < roi.y0 || y >= roi.y1) ? 0 : m.row(y)[x];
}

// Sums of R, G, B and a count.
struct ColourSum {
	int64_t c[3] = { 0, 0, 0 };
	int64_t n = 0;
	void add(Rgb8 p)
	{
		c[0] += p.r;
		c[1] += p.g;
		c[2] += p.b;
		++n;
	}
};

} // namespace

int BoundaryUnmixingWholeRoi::refine(const RgbImage &colour, const Gray8Image &trimap, const BoardModel &board, const Roi &roi,
			     Gray8Image &matte)
{
	if (minContrast2_ <= 0 || roi.empty() || board.empty())
		return 0;
	kind_.resize(matte.width(), matte.height());
	int changed = 0;
	for (int p = 0; p < kPasses; ++p)
		changed += pass(colour, trimap, board, roi, matte);
	return changed;
}

int BoundaryUnmixingWholeRoi::pass(const RgbImage &colour, const Gray8Image &trimap, const BoardModel &board, const Roi &roi,
			   Gray8Image &matte)
{
	// What each pixel is before this pass (the pass reads kinds only, so
	// what it turns to lecturer counts from the next pass on).
	for (int y = roi.y0; y < roi.y1; ++y) {
		uint8_t *k = kind_.row(y);
		// The ROI's border columns and rows see board beyond it; inside,
		// row pointers (this runs over the whole ROI, three times a frame).
		const uint8_t *up = y > roi.y0 ? matte.row(y - 1) : nullptr;
		const uint8_t *m = matte.row(y);
		const uint8_t *down = y + 1 < roi.y1 ? matte.row(y + 1) : nullptr;
		for (int x = roi.x0; x < roi.x1; ++x) {
			const bool inner = x > roi.x0 && x + 1 < roi.x1 && up && down;
			const int around = inner ? m[x] + m[x - 1] + m[x + 1] + up[x] + down[x]
						 : at(matte, roi, x, y) + at(matte, roi, x - 1, y) + at(matte, roi, x + 1, y) +
							   at(matte, roi, x, y - 1) + at(matte, roi, x, y + 1);
			k[x] = around == 5 * 255 ? kLecturerInside
			       : around == 0	 ? kBoardInside
			       : m[x]		 ? kLecturerEdge
						 : kBoardEdge;
		}
	}
	const int *gain = board.gainQ8();
	int changed = 0;
	for (int y = roi.y0; y < roi.y1; ++y) {
		const Rgba8 *model = board.row(y);
		for (int x = roi.x0; x < roi.x1; ++x) {
			const uint8_t label = trimap.row(y)[x];
			if (kind_.row(y)[x] != kBoardEdge || label == kTrimapBoard)
				continue;
			ColourSum lecturer, near;
			const int wy0 = std::max(roi.y0, y - kWindowRadius), wy1 = std::min(roi.y1, y + kWindowRadius + 1);
			const int wx0 = std::max(roi.x0, x - kWindowRadius), wx1 = std::min(roi.x1, x + kWindowRadius + 1);
			for (int wy = wy0; wy < wy1; ++wy) {
				const uint8_t *k = kind_.row(wy);
				const Rgb8 *c = colour.row(wy);
				for (int wx = wx0; wx < wx1; ++wx) {
					if (k[wx] == kLecturerInside)
						lecturer.add(c[wx]);
					else if (k[wx] == kBoardInside)
						near.add(c[wx]);
				}
			}
			if (lecturer.n == 0 || near.n == 0)
				continue; // no side to compare with: a speck, a one-pixel line
			// B n and F n - B n, I n - B n: in units of 1/n level.
			const int64_t n = lecturer.n;
			const Rgba8 m = model[x];
			const bool learned = m.a >= BoardModel::kLearnedVisits;
			const int64_t boardLevel[3] = {
				learned ? (m.r * gain[0] + 128) >> 8 : 0,
				learned ? (m.g * gain[1] + 128) >> 8 : 0,
				learned ? (m.b * gain[2] + 128) >> 8 : 0,
			};
			const Rgb8 px = colour.row(y)[x];
			const int64_t level[3] = { px.r, px.g, px.b };
			int64_t dot = 0, norm = 0;
			for (int c = 0; c < 3; ++c) {
				// Unlearned: the local board mean, rescaled to 1/n units.
				const int64_t bn = learned ? boardLevel[c] * n : (near.c[c] * n + near.n / 2) / near.n;
				const int64_t d = lecturer.c[c] - bn;
				norm += d * d;
				dot += (level[c] * n - bn) * d;
			}
			if (norm < int64_t(minContrast2_) * n * n)
				continue;
			if (2 * dot >= norm) {
				matte.row(y)[x] = 255;
				++changed;
			}
		}
	}
	return changed;
}

} // namespace depthkey::test
