#include "algo/band_components.hpp"

#include <cstring>
#include <utility>

namespace depthkey {

namespace {

// Marks of a decision's band runs while their regions are resolved; the
// mask otherwise holds only 0, 255 and kBandOutside.
constexpr uint8_t kMarkedLecturer = 1;
constexpr uint8_t kMarkedBoard = 2;

} // namespace

void BandComponents::reserve(size_t bandPixels)
{
	// A run is at least one pixel.
	if (runs_.capacity() < bandPixels)
		runs_.reserve(bandPixels);
}

int32_t BandComponents::find(int32_t r)
{
	while (runs_[size_t(r)].parent != r) {
		Run &run = runs_[size_t(r)];
		run.parent = runs_[size_t(run.parent)].parent; // path halving
		r = run.parent;
	}
	return r;
}

void BandComponents::join(int32_t a, int32_t b)
{
	a = find(a);
	b = find(b);
	if (a == b)
		return;
	if (runs_[size_t(a)].size < runs_[size_t(b)].size)
		std::swap(a, b);
	runs_[size_t(b)].parent = a;
	runs_[size_t(a)].size += runs_[size_t(b)].size;
}

void BandComponents::collect(uint8_t *mask, int stride, const std::vector<BandSpan> &spans, uint8_t value,
			     uint8_t mark)
{
	runs_.clear();
	for (const BandSpan &s : spans) {
		const int rowStart = (s.y + 1) * stride + 1;
		for (int x = s.x0; x < s.x1;) {
			while (x < s.x1 && mask[rowStart + x] != value)
				++x;
			const int x0 = x;
			for (; x < s.x1 && mask[rowStart + x] == value; ++x)
				mask[rowStart + x] = mark;
			if (x == x0)
				break;
			const int32_t index = int32_t(runs_.size());
			runs_.push_back({ rowStart + x0, x - x0, s.first + (x0 - s.x0), s.y, x0, index, uint32_t(x - x0),
					  false });
		}
	}
	// Join the runs of each row with the overlapping runs of the row
	// above: the runs are in row order, and in x order within a row.
	const int32_t count = int32_t(runs_.size());
	int32_t above = 0, aboveEnd = 0; // the previous row's runs
	for (int32_t row = 0; row < count;) {
		const int y = runs_[size_t(row)].y;
		int32_t rowEnd = row;
		while (rowEnd < count && runs_[size_t(rowEnd)].y == y)
			++rowEnd;
		if (above < aboveEnd && runs_[size_t(above)].y == y - 1) {
			for (int32_t i = above, j = row; i < aboveEnd && j < rowEnd;) {
				const Run &a = runs_[size_t(i)], &b = runs_[size_t(j)];
				const int aEnd = a.x0 + a.n, bEnd = b.x0 + b.n;
				if (a.x0 < bEnd && b.x0 < aEnd)
					join(i, j);
				if (aEnd < bEnd)
					++i;
				else
					++j;
			}
		}
		above = row;
		aboveEnd = rowEnd;
		row = rowEnd;
	}
}

template<typename Anchor>
void BandComponents::anchor(const uint8_t *mask, int stride, Anchor isAnchor)
{
	for (int32_t r = 0; r < int32_t(runs_.size()); ++r) {
		Run &root = runs_[size_t(find(r))];
		if (root.anchored)
			continue; // a run before it already anchored its region
		const Run &run = runs_[size_t(r)];
		const uint8_t *up = mask + run.p - stride, *down = mask + run.p + stride;
		bool found = isAnchor(mask[run.p - 1]) || isAnchor(mask[run.p + run.n]);
		for (int i = 0; i < run.n && !found; ++i)
			found = isAnchor(up[i]) || isAnchor(down[i]);
		root.anchored = found;
	}
}

void BandComponents::keepTouchingLecturer(uint8_t *mask, int stride, const std::vector<BandSpan> &spans,
					  bool lecturerBeyondBorder, size_t minKeep)
{
	collect(mask, stride, spans, 255, kMarkedLecturer);
	// Every band lecturer pixel is marked now, so a 255 beside a run is a
	// surely-lecturer seed.
	anchor(mask, stride,
	       [&](uint8_t v) { return v == 255 || (v == kBandOutside && lecturerBeyondBorder); });
	for (int32_t r = 0; r < int32_t(runs_.size()); ++r) {
		const Run &root = runs_[size_t(find(r))];
		const Run &run = runs_[size_t(r)];
		std::memset(mask + run.p, root.anchored || root.size >= minKeep ? 255 : 0, size_t(run.n));
	}
}

void BandComponents::fillHoles(uint8_t *mask, int stride, const std::vector<BandSpan> &spans,
			       const uint8_t *confidence, uint8_t clearlyBoard)
{
	collect(mask, stride, spans, 0, kMarkedBoard);
	// Board seeds and the image border are where the board goes on.
	anchor(mask, stride, [](uint8_t v) { return v == 0 || v == kBandOutside; });
	for (int32_t r = 0; r < int32_t(runs_.size()); ++r) {
		const Run &run = runs_[size_t(r)];
		uint8_t *m = mask + run.p;
		if (runs_[size_t(find(r))].anchored) {
			std::memset(m, 0, size_t(run.n));
			continue;
		}
		const uint8_t *c = confidence + run.k;
		for (int i = 0; i < run.n; ++i)
			m[i] = c[i] < clearlyBoard ? 0 : 255;
	}
}

} // namespace depthkey
