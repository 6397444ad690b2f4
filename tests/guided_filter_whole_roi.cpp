// The pre-issue-28 guided filter, unchanged but for its name (see the header).
#include "tests/guided_filter_whole_roi.hpp"

#include <algorithm>
#include <array>
#include <cstring>

namespace depthkey::test {

namespace {

// The sums of K column-sum rows over a window of columns [x - r, x + r]
// clipped to [0, w), slid one column at a time, modulo 2^32.
template<size_t K>
struct SlidingSums {
	std::array<const uint32_t *, K> columns;
	std::array<uint32_t, K> sums{};

	void add(int x, uint32_t sign)
	{
		for (size_t k = 0; k < K; ++k)
			sums[k] += sign * columns[k][x];
	}
	// The window of x = -1: columns [0, r).
	void start(int r, int w)
	{
		for (int x = 0; x < std::min(w, r); ++x)
			add(x, 1u);
	}
	// The window of x from that of x - 1.
	void advance(int x, int r, int w)
	{
		if (x + r < w)
			add(x + r, 1u);
		if (x - r - 1 >= 0)
			add(x - r - 1, ~0u);
	}
};

} // namespace

void GuidedFilterWholeRoi::configure(int radius, int eps)
{
	radius_ = std::clamp(radius, 1, kMaxRadius);
	eps_ = std::max(1, eps);
}

void GuidedFilterWholeRoi::markNearEdges(const Gray8Image &matte, const Roi &roi)
{
	const int w = roi.x1 - roi.x0, h = roi.y1 - roi.y0, r = radius_;
	auto P = [&](int x, int y) { return matte.row(roi.y0 + y)[roi.x0 + x]; };
	for (int y = 0; y < h; ++y)
		for (int x = 0; x < w; ++x) {
			const uint8_t p = P(x, y);
			const bool edge = (x + 1 < w && P(x + 1, y) != p) || (y + 1 < h && P(x, y + 1) != p);
			if (!edge)
				continue;
			// A window holding both pixels of this edge is centred within r
			// of them (its a, b are not 0, p); a pixel holding such a window
			// lies within 2r. Mark that square.
			for (int yy = std::max(0, y - 2 * r); yy <= std::min(h - 1, y + 2 * r + 1); ++yy)
				std::memset(near_.row(roi.y0 + yy) + roi.x0 + std::max(0, x - 2 * r), 1,
					    size_t(std::min(w - 1, x + 2 * r + 1) - std::max(0, x - 2 * r) + 1));
		}
}

void GuidedFilterWholeRoi::coefficientsRow(const Gray8Image &matte, const Roi &roi, int y)
{
	const int w = roi.x1 - roi.x0, h = roi.y1 - roi.y0, r = radius_;
	// The window's rows: [y - r, y + r] clipped to the ROI.
	auto moments = [&](int row, uint32_t sign) {
		const uint8_t *g = guide_.row(roi.y0 + row) + roi.x0, *m = matte.row(roi.y0 + row) + roi.x0;
		for (int x = 0; x < w; ++x) {
			const uint32_t i = g[x], p = m[x];
			colI_[x] += sign * i;
			colP_[x] += sign * p;
			colII_[x] += sign * (i * i);
			colIP_[x] += sign * (i * p);
		}
	};
	for (; momentEnd_ < std::min(h, y + r + 1); ++momentEnd_)
		moments(momentEnd_, 1u);
	for (; momentTop_ < y - r; ++momentTop_)
		moments(momentTop_, ~0u); // minus, modulo 2^32
	const int64_t rows = momentEnd_ - momentTop_;

	const uint8_t *nr = near_.row(roi.y0 + y) + roi.x0, *pRow = matte.row(roi.y0 + y) + roi.x0;
	int32_t *aRow = a_.data() + size_t(y % ringRows()) * w, *bRow = b_.data() + size_t(y % ringRows()) * w;
	SlidingSums<4> window{ { colI_.data(), colP_.data(), colII_.data(), colIP_.data() } };
	window.start(r, w);
	for (int x = 0; x < w; ++x) {
		window.advance(x, r, w);
		if (!nr[x]) {
			aRow[x] = 0;
			bRow[x] = int32_t(pRow[x]) << 8;
			continue;
		}
		const int64_t N = int64_t(std::min(w, x + r + 1) - std::max(0, x - r)) * rows;
		const int64_t I = window.sums[0], P = window.sums[1], II = window.sums[2], IP = window.sums[3];
		// a = (N sIP - sI sP) / (N sII - sI^2 + eps N^2), in Q16; then
		// b = (sP - a sI) / N in Q8. Both rounded to nearest.
		const int64_t cov = N * IP - I * P, var = N * II - I * I + int64_t(eps_) * N * N;
		const int64_t num = cov * 65536;
		const int64_t a = (num >= 0 ? num + var / 2 : num - var / 2) / var;
		const int64_t bNum = (P << 16) - a * I; // Q16 * N
		const int64_t bDen = N * 256;
		aRow[x] = int32_t(a);
		bRow[x] = int32_t((bNum >= 0 ? bNum + bDen / 2 : bNum - bDen / 2) / bDen);
	}
}

void GuidedFilterWholeRoi::outputRow(const Gray8Image &matte, const Roi &roi, int y, Gray8Image &out)
{
	const int w = roi.x1 - roi.x0, h = roi.y1 - roi.y0, r = radius_;
	// The ring's rows in y's window; coefficientsRow() has made them.
	auto coefficients = [&](int row, uint32_t sign) {
		const int32_t *a = a_.data() + size_t(row % ringRows()) * w, *b = b_.data() + size_t(row % ringRows()) * w;
		for (int x = 0; x < w; ++x) {
			colA_[x] += sign * uint32_t(a[x]);
			colB_[x] += sign * uint32_t(b[x]);
		}
	};
	for (; ringEnd_ < std::min(h, y + r + 1); ++ringEnd_)
		coefficients(ringEnd_, 1u);
	for (; ringTop_ < y - r; ++ringTop_)
		coefficients(ringTop_, ~0u);
	const int64_t rows = ringEnd_ - ringTop_;

	uint8_t *o = out.row(roi.y0 + y) + roi.x0;
	const uint8_t *nr = near_.row(roi.y0 + y) + roi.x0, *pRow = matte.row(roi.y0 + y) + roi.x0;
	const uint8_t *g = guide_.row(roi.y0 + y) + roi.x0;
	SlidingSums<2> window{ { colA_.data(), colB_.data() } };
	window.start(r, w);
	for (int x = 0; x < w; ++x) {
		window.advance(x, r, w);
		const uint8_t p = pRow[x];
		if (!nr[x]) {
			o[x] = p;
			continue;
		}
		const int64_t N = int64_t(std::min(w, x + r + 1) - std::max(0, x - r)) * rows;
		// q = (sA I / 2^16 + sB / 2^8) / N, rounded; the sums' true values
		// fit int32.
		const int64_t num = int64_t(int32_t(window.sums[0])) * g[x] + int64_t(int32_t(window.sums[1])) * 256;
		const int64_t den = N * 65536;
		const int64_t q = (num >= 0 ? num + den / 2 : num - den / 2) / den;
		o[x] = uint8_t(std::clamp<int64_t>(q, 0, 255));
		changed_ += o[x] != p;
	}
}

void GuidedFilterWholeRoi::filter(const RgbImage &colour, const Gray8Image &matte, const Roi &roi, Gray8Image &out)
{
	const int W = colour.width(), H = colour.height();
	out.resize(W, H);
	changed_ = 0;
	if (roi.empty())
		return;
	const int w = roi.x1 - roi.x0, h = roi.y1 - roi.y0, r = radius_;
	guide_.resize(W, H);
	near_.resize(W, H);
	// Sized for the whole width and the largest radius once, so that no
	// frame allocates whatever the ROI.
	for (auto *s : { &colI_, &colP_, &colII_, &colIP_, &colA_, &colB_ }) {
		if (s->size() < size_t(W))
			s->resize(size_t(W));
		std::fill(s->begin(), s->begin() + w, 0u);
	}
	const size_t ring = size_t(2 * kMaxRadius + 2) * W;
	if (a_.size() < ring) {
		a_.resize(ring);
		b_.resize(ring);
	}
	momentTop_ = momentEnd_ = ringTop_ = ringEnd_ = 0;

	// Luma (r + 2g + b) / 4, and the pixels near an edge of the matte.
	for (int y = roi.y0; y < roi.y1; ++y) {
		const Rgb8 *c = colour.row(y);
		uint8_t *g = guide_.row(y), *nr = near_.row(y);
		for (int x = roi.x0; x < roi.x1; ++x) {
			g[x] = uint8_t((c[x].r + 2 * c[x].g + c[x].b + 2) >> 2);
			nr[x] = 0;
		}
	}
	markNearEdges(matte, roi);

	// Row y's q needs a and b up to row y + r: the output runs r rows behind.
	for (int y = 0; y < h; ++y) {
		coefficientsRow(matte, roi, y);
		if (y - r >= 0)
			outputRow(matte, roi, y - r, out);
	}
	for (int y = std::max(0, h - r); y < h; ++y)
		outputRow(matte, roi, y, out);
}

} // namespace depthkey::test
