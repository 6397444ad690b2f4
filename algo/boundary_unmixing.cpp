#include "algo/boundary_unmixing.hpp"

#include "algo/column_sums.hpp"
#include "algo/edge_kinds_rows.hpp"

#include <algorithm>
#include <climits>
#include <cstring>

namespace depthkey {

namespace {

// The matte at (x, y): 0 outside roi (board there).
inline uint8_t at(const Gray8Image &m, const Roi &roi, int x, int y)
{
	return (x < roi.x0 || x >= roi.x1 || y < roi.y0 || y >= roi.y1) ? 0 : m.row(y)[x];
}

// Whether one of the eight kinds at k is 0 (kBoardEdge): most of the ROI
// is inside one side, skipped eight pixels at a time.
inline bool anyBoardEdge(const uint8_t *k)
{
	uint64_t v;
	std::memcpy(&v, k, sizeof v);
	return ((v - 0x0101010101010101ull) & ~v & 0x8080808080808080ull) != 0;
}

} // namespace

uint8_t BoundaryUnmixing::kindAt(const Gray8Image &matte, const Roi &roi, int x, int y)
{
	return kindOf(at(matte, roi, x, y) + at(matte, roi, x - 1, y) + at(matte, roi, x + 1, y) + at(matte, roi, x, y - 1) +
			      at(matte, roi, x, y + 1),
		      matte.row(y)[x]);
}

int BoundaryUnmixing::refine(const RgbImage &colour, const Gray8Image &trimap, const BoardModel &board, const Roi &roi,
			     Gray8Image &matte)
{
	if (minContrast2_ <= 0 || roi.empty() || board.empty())
		return 0;
	const int W = matte.width(), H = matte.height();
	// Sized for the whole image once: no frame allocates whatever the ROI.
	kind_.resize(W, H);
	if (turnedX0_.size() < size_t(H)) {
		turnedX0_.resize(size_t(H));
		turnedX1_.resize(size_t(H));
	}
	for (auto &c : columns_)
		if (c.size() < size_t(W))
			c.resize(size_t(W));
	if (columnRow_.size() < size_t(W)) {
		columnRow_.resize(size_t(W));
		zeroKinds_.resize(size_t(W));
		zeroColours_.resize(size_t(W));
	}
	findKinds(matte, roi);
	int changed = 0;
	for (int p = 0; p < kPasses; ++p) {
		changed += pass(colour, trimap, board, roi, matte);
		if (p + 1 < kPasses)
			updateKinds(matte, roi);
	}
	return changed;
}

void BoundaryUnmixing::findKinds(const Gray8Image &matte, const Roi &roi)
{
	for (int y = roi.y0; y < roi.y1; ++y) {
		uint8_t *k = kind_.row(y);
		// The ROI's border columns and rows see board beyond it; inside,
		// row pointers.
		if (y == roi.y0 || y + 1 == roi.y1 || roi.x1 - roi.x0 < 3) {
			for (int x = roi.x0; x < roi.x1; ++x)
				k[x] = kindAt(matte, roi, x, y);
			continue;
		}
		const uint8_t *up = matte.row(y - 1), *m = matte.row(y), *down = matte.row(y + 1);
		k[roi.x0] = kindAt(matte, roi, roi.x0, y);
		edgeKinds_(up + roi.x0 + 1, m + roi.x0 + 1, down + roi.x0 + 1, roi.x1 - roi.x0 - 2, k + roi.x0 + 1);
		k[roi.x1 - 1] = kindAt(matte, roi, roi.x1 - 1, y);
	}
}

void BoundaryUnmixing::updateKinds(const Gray8Image &matte, const Roi &roi)
{
	// Only a turned pixel's and its 4-neighbours' sums changed. Neighbours
	// first, while every turned pixel still says so; then the turned.
	static constexpr int kDx[4] = { -1, 1, 0, 0 }, kDy[4] = { 0, 0, -1, 1 };
	for (int y = roi.y0; y < roi.y1; ++y)
		for (int x = turnedX0_[size_t(y)]; x < turnedX1_[size_t(y)]; ++x) {
			if (kind_.row(y)[x] != kTurned)
				continue;
			for (int d = 0; d < 4; ++d) {
				const int nx = x + kDx[d], ny = y + kDy[d];
				if (nx >= roi.x0 && nx < roi.x1 && ny >= roi.y0 && ny < roi.y1 && kind_.row(ny)[nx] != kTurned)
					kind_.row(ny)[nx] = kindAt(matte, roi, nx, ny);
			}
		}
	for (int y = roi.y0; y < roi.y1; ++y)
		for (int x = turnedX0_[size_t(y)]; x < turnedX1_[size_t(y)]; ++x)
			if (kind_.row(y)[x] == kTurned)
				kind_.row(y)[x] = kindAt(matte, roi, x, y);
}

int BoundaryUnmixing::pass(const RgbImage &colour, const Gray8Image &trimap, const BoardModel &board, const Roi &roi,
			   Gray8Image &matte)
{
	// In ROI coordinates: the window's rows and columns clipped to the ROI.
	const int w = roi.x1 - roi.x0, h = roi.y1 - roi.y0, R = kWindowRadius;
	std::fill(columnRow_.begin(), columnRow_.begin() + w, INT_MIN); // no column holds a window
	std::fill(turnedX0_.begin() + roi.y0, turnedX0_.begin() + roi.y1, 0);
	std::fill(turnedX1_.begin() + roi.y0, turnedX1_.begin() + roi.y1, 0);
	// The lecturer's inside pixels' R, G, B and count, then the board's.
	auto sides = [&](int row, int x) {
		const uint8_t k = kind_.row(roi.y0 + row)[roi.x0 + x];
		const Rgb8 c = colour.row(roi.y0 + row)[roi.x0 + x];
		const uint32_t l = k == kLecturerInside, b = k == kBoardInside;
		return std::array<uint32_t, 8>{ l * c.r, l * c.g, l * c.b, l, b * c.r, b * c.g, b * c.b, b };
	};
	std::array<uint32_t *, 8> sums;
	std::array<const uint32_t *, 8> constSums;
	for (size_t i = 0; i < 8; ++i)
		constSums[i] = sums[i] = columns_[i].data();
	ColumnSums<8> columns{ sums, columnRow_.data() };
	const int *gain = board.gainQ8();
	int changed = 0;
	for (int y = 0; y < h; ++y) {
		uint8_t *k = kind_.row(roi.y0 + y) + roi.x0;
		const uint8_t *label = trimap.row(roi.y0 + y) + roi.x0;
		auto looked = [&](int x) { return k[x] == kBoardEdge && label[x] != kTrimapBoard; };
		// The rows the window's column sums take in and off, moving down
		// (kBoardEdge, 0, is neither side).
		static_assert(kBoardEdge == 0);
		const bool in = y + R < h, out = y - R - 1 >= 0;
		const uint8_t *kIn = in ? kind_.row(roi.y0 + y + R) + roi.x0 : zeroKinds_.data();
		const uint8_t *kOut = out ? kind_.row(roi.y0 + y - R - 1) + roi.x0 : zeroKinds_.data();
		const Rgb8 *cIn = in ? colour.row(roi.y0 + y + R) + roi.x0 : zeroColours_.data();
		const Rgb8 *cOut = out ? colour.row(roi.y0 + y - R - 1) + roi.x0 : zeroColours_.data();
		auto step = [&](int s, int e) {
			SideSums at;
			for (size_t i = 0; i < at.size(); ++i)
				at[i] = sums[i] + s;
			sideColumns_(kIn + s, cIn + s, kOut + s, cOut + s, e - s, { kLecturerInside, kBoardInside }, at);
		};
		for (int from = 0, s, e;; from = e) {
			// The next run [s, e) of undecided board pixels on the edge.
			while (from + 8 <= w && !anyBoardEdge(k + from))
				from += 8;
			while (from < w && !looked(from))
				++from;
			if (from == w)
				break;
			for (s = e = from; e < w && looked(e);)
				++e;
			columns.bringRun(std::max(0, s - R), std::min(w, e + R), y, R, h, sides, step);
			SlidingSums<8> window{ constSums };
			window.start(s, R, w);
			for (int x = s; x < e; ++x) {
				window.advance(x, R, w);
				const int64_t n = window.sums[3], nearN = window.sums[7];
				if (n == 0 || nearN == 0)
					continue; // no side to compare with: a speck, a one-pixel line
				// B n and F n - B n, I n - B n: in units of 1/n level.
				const Rgba8 m = board.row(roi.y0 + y)[roi.x0 + x];
				const bool learned = m.a >= BoardModel::kLearnedVisits;
				const int64_t boardLevel[3] = {
					learned ? (m.r * gain[0] + 128) >> 8 : 0,
					learned ? (m.g * gain[1] + 128) >> 8 : 0,
					learned ? (m.b * gain[2] + 128) >> 8 : 0,
				};
				const Rgb8 px = colour.row(roi.y0 + y)[roi.x0 + x];
				const int64_t level[3] = { px.r, px.g, px.b };
				int64_t dot = 0, norm = 0;
				for (int c = 0; c < 3; ++c) {
					// Unlearned: the local board mean, rescaled to 1/n units.
					const int64_t near = window.sums[4 + c];
					const int64_t bn = learned ? boardLevel[c] * n : (near * n + nearN / 2) / nearN;
					const int64_t d = int64_t(window.sums[c]) - bn;
					norm += d * d;
					dot += (level[c] * n - bn) * d;
				}
				if (norm < int64_t(minContrast2_) * n * n)
					continue;
				if (2 * dot >= norm) {
					// Turned: neither side for the rest of this pass, as
					// before (kinds are what they were when it began).
					matte.row(roi.y0 + y)[roi.x0 + x] = 255;
					k[x] = kTurned;
					int &x0 = turnedX0_[size_t(roi.y0 + y)], &x1 = turnedX1_[size_t(roi.y0 + y)];
					x0 = x1 == 0 ? roi.x0 + x : x0;
					x1 = roi.x0 + x + 1;
					++changed;
				}
			}
		}
	}
	return changed;
}

} // namespace depthkey
