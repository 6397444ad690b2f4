#include "algo/guided_filter.hpp"

#include "algo/column_sums.hpp"

#include <algorithm>
#include <bit>
#include <climits>
#include <cstring>

namespace depthkey {

namespace {

// The next run [s, e) of near pixels at or after from; false if none.
bool nextRun(const uint8_t *near, int from, int w, int &s, int &e)
{
	int x = from;
	// Eight at a time across the far field, most of the ROI.
	for (uint64_t v; x + 8 <= w; x += 8) {
		std::memcpy(&v, near + x, sizeof v);
		if (v)
			break;
	}
	while (x < w && !near[x])
		++x;
	if (x == w)
		return false;
	s = x;
	while (x < w && near[x])
		++x;
	e = x;
	return true;
}

// n / (N 2^shift) rounded half away from zero, as (n +- den / 2) / den
// with den = N 2^shift gives it: floor((|n| + den / 2) / den) is
// floor(floor((|n| + den / 2) / 2^shift) / N) (a floor of a floor), the
// first a shift, the second byN's multiply while it is below 2^31 (the
// callers' are: |n| / 2^shift < 2^30 N), else a division.
inline int64_t roundedQuotient(int64_t n, int shift, int64_t N, const ExactDivisor &byN)
{
	const uint64_t magnitude = uint64_t(n >= 0 ? n : -n);
	const uint64_t m = (magnitude + (uint64_t(N) << (shift - 1))) >> shift;
	const int64_t q = m < (uint64_t(1) << ExactDivisor::kNumeratorBits) ? int64_t(byN.floor(uint32_t(m)))
									    : int64_t(m / uint64_t(N));
	return n >= 0 ? q : -q;
}

} // namespace

GuidedFilter::GuidedFilter()
{
	for (int n = 1; n <= kMaxWindowPixels; ++n)
		byCount_[size_t(n)].set(uint32_t(n));
}

void GuidedFilter::configure(int radius, int eps)
{
	radius_ = std::clamp(radius, 1, kMaxRadius);
	eps_ = std::max(1, eps);
}

void GuidedFilter::markNearEdges(const Gray8Image &matte, const Roi &roi)
{
	const int w = roi.x1 - roi.x0, h = roi.y1 - roi.y0, r = radius_, rows = 4 * r + 3;
	const int stride = (w + 7) & ~7; // whole words, the padding 0
	constexpr uint64_t kOnes = 0x0101010101010101ull, kLow7 = 0x7f7f7f7f7f7f7f7full;
	auto word = [](const uint8_t *p) {
		uint64_t v;
		std::memcpy(&v, p, sizeof v);
		return v;
	};
	// An edge between a pixel (x, y) and its right or lower neighbour: a
	// window holding both is centred within r of them (its a, b are not 0,
	// p), and a pixel holding such a window lies within 2r, in
	// [x - 2r, x + 2r + 1] x [y - 2r, y + 2r + 1]. Along a row, those
	// spans are set (edges are few: eight pixels are compared at a time);
	// along columns, a byte per column counts the rows' spans that reach it
	// (at most 4r + 2), eight columns a word.
	auto alongRow = [&](int y) {
		const uint8_t *m = matte.row(roi.y0 + y) + roi.x0;
		const uint8_t *below = y + 1 < h ? matte.row(roi.y0 + y + 1) + roi.x0 : m;
		uint8_t *out = alongRows_.data() + size_t(y % rows) * stride;
		std::memset(out, 0, size_t(stride));
		int setEnd = 0;
		auto mark = [&](int x) {
			const int from = std::max(setEnd, x - 2 * r), to = std::min(w, x + 2 * r + 2);
			if (from < to)
				std::memset(out + from, 1, size_t(to - from));
			setEnd = std::max(setEnd, to);
		};
		int x = 0;
		for (; x + 9 <= w; x += 8)
			// A byte not 0: that pixel differs from its right or lower one.
			for (uint64_t d = (word(m + x + 1) ^ word(m + x)) | (word(below + x) ^ word(m + x)); d;) {
				const int byte = std::countr_zero(d) / 8;
				mark(x + byte);
				d &= ~(uint64_t(0xff) << (8 * byte));
			}
		for (; x < w; ++x)
			if ((x + 1 < w && m[x + 1] != m[x]) || below[x] != m[x])
				mark(x);
	};
	auto addRow = [&](int y, bool add) {
		const uint8_t *a = alongRows_.data() + size_t(y % rows) * stride;
		for (int x = 0; x < stride; x += 8) {
			// Bytes of 0..4r + 2: no carry nor borrow crosses a byte.
			const uint64_t v = word(reach_.data() + x), d = word(a + x);
			const uint64_t sum = add ? v + d : v - d;
			std::memcpy(reach_.data() + x, &sum, sizeof sum);
		}
	};
	std::fill(reach_.begin(), reach_.begin() + stride, 0);
	for (int y = 0; y < std::min(h, 2 * r); ++y) {
		alongRow(y);
		addRow(y, true);
	}
	for (int y = 0; y < h; ++y) {
		if (y + 2 * r < h) {
			alongRow(y + 2 * r);
			addRow(y + 2 * r, true);
		}
		if (y - 2 * r - 2 >= 0)
			addRow(y - 2 * r - 2, false);
		uint8_t *nr = near_.row(roi.y0 + y) + roi.x0;
		int x = 0;
		for (; x + 8 <= w; x += 8) {
			// 1 in each byte that is not 0.
			const uint64_t v = word(reach_.data() + x), any = (((v & kLow7) + kLow7) | v) >> 7 & kOnes;
			std::memcpy(nr + x, &any, sizeof any);
		}
		for (; x < w; ++x)
			nr[x] = reach_[x] != 0;
	}
}

void GuidedFilter::coefficientsRow(const Gray8Image &matte, const Roi &roi, int y)
{
	const int w = roi.x1 - roi.x0, h = roi.y1 - roi.y0, r = radius_;
	const uint8_t *nr = near_.row(roi.y0 + y) + roi.x0, *pRow = matte.row(roi.y0 + y) + roi.x0;
	int32_t *aRow = a_.data() + size_t(y % ringRows()) * w, *bRow = b_.data() + size_t(y % ringRows()) * w;
	// Off the edge the window's p is constant: a = 0, b = p. The output's
	// windows read those too.
	for (int x = 0; x < w; ++x) {
		aRow[x] = 0;
		bRow[x] = int32_t(pRow[x]) << 8;
	}
	const int64_t rows = std::min(h, y + r + 1) - std::max(0, y - r);
	auto moments = [&](int row, int x) {
		const uint32_t i = guide_.row(roi.y0 + row)[roi.x0 + x], p = matte.row(roi.y0 + row)[roi.x0 + x];
		return std::array<uint32_t, 4>{ i, p, i * i, i * p };
	};
	ColumnSums<4> columns{ { colI_.data(), colP_.data(), colII_.data(), colIP_.data() }, momentRow_.data() };
	// The rows the window's column sums take in and off, moving down.
	const bool in = y + r < h, out = y - r - 1 >= 0;
	const uint8_t *iIn = in ? guide_.row(roi.y0 + y + r) + roi.x0 : zeroBytes_.data();
	const uint8_t *pIn = in ? matte.row(roi.y0 + y + r) + roi.x0 : zeroBytes_.data();
	const uint8_t *iOut = out ? guide_.row(roi.y0 + y - r - 1) + roi.x0 : zeroBytes_.data();
	const uint8_t *pOut = out ? matte.row(roi.y0 + y - r - 1) + roi.x0 : zeroBytes_.data();
	auto step = [&](int s, int e) {
		momentColumns_(iIn + s, pIn + s, iOut + s, pOut + s, e - s,
			       { colI_.data() + s, colP_.data() + s, colII_.data() + s, colIP_.data() + s });
	};
	for (int s, e, from = 0; nextRun(nr, from, w, s, e); from = e) {
		columns.bringRun(std::max(0, s - r), std::min(w, e + r), y, r, h, moments, step);
		SlidingSums<4> window{ { colI_.data(), colP_.data(), colII_.data(), colIP_.data() } };
		window.start(s, r, w);
		for (int x = s; x < e; ++x) {
			window.advance(x, r, w);
			const int64_t N = int64_t(std::min(w, x + r + 1) - std::max(0, x - r)) * rows;
			const int64_t I = window.sums[0], P = window.sums[1], II = window.sums[2], IP = window.sums[3];
			// a = (N sIP - sI sP) / (N sII - sI^2 + eps N^2), in Q16; then
			// b = (sP - a sI) / N in Q8. Both rounded to nearest.
			const int64_t cov = N * IP - I * P, var = N * II - I * I + int64_t(eps_) * N * N;
			const int64_t num = cov * 65536;
			const int64_t a = (num >= 0 ? num + var / 2 : num - var / 2) / var;
			const int64_t bNum = (P << 16) - a * I; // Q16 * N
			aRow[x] = int32_t(a);
			bRow[x] = int32_t(roundedQuotient(bNum, 8, N, byCount_[size_t(N)]));
		}
	}
}

void GuidedFilter::outputRow(const Gray8Image &matte, const Roi &roi, int y, Gray8Image &out)
{
	const int w = roi.x1 - roi.x0, h = roi.y1 - roi.y0, r = radius_;
	uint8_t *o = out.row(roi.y0 + y) + roi.x0;
	const uint8_t *nr = near_.row(roi.y0 + y) + roi.x0, *pRow = matte.row(roi.y0 + y) + roi.x0;
	const uint8_t *g = guide_.row(roi.y0 + y) + roi.x0;
	std::memcpy(o, pRow, size_t(w)); // off the edge q = p
	const int64_t rows = std::min(h, y + r + 1) - std::max(0, y - r);
	// The ring's rows in y's window; coefficientsRow() has made them.
	auto coefficients = [&](int row, int x) {
		const size_t at = size_t(row % ringRows()) * w + size_t(x);
		return std::array<uint32_t, 2>{ uint32_t(a_[at]), uint32_t(b_[at]) };
	};
	ColumnSums<2> columns{ { colA_.data(), colB_.data() }, ringRow_.data() };
	const bool takeIn = y + r < h, takeOff = y - r - 1 >= 0;
	auto ringAt = [&](const std::vector<int32_t> &ring, int row) { return ring.data() + size_t(row % ringRows()) * w; };
	const int32_t *aIn = takeIn ? ringAt(a_, y + r) : zeroWords_.data();
	const int32_t *bIn = takeIn ? ringAt(b_, y + r) : zeroWords_.data();
	const int32_t *aOut = takeOff ? ringAt(a_, y - r - 1) : zeroWords_.data();
	const int32_t *bOut = takeOff ? ringAt(b_, y - r - 1) : zeroWords_.data();
	auto step = [&](int s, int e) {
		pairColumns_(aIn + s, bIn + s, aOut + s, bOut + s, e - s, { colA_.data() + s, colB_.data() + s });
	};
	for (int s, e, from = 0; nextRun(nr, from, w, s, e); from = e) {
		columns.bringRun(std::max(0, s - r), std::min(w, e + r), y, r, h, coefficients, step);
		SlidingSums<2> window{ { colA_.data(), colB_.data() } };
		window.start(s, r, w);
		for (int x = s; x < e; ++x) {
			window.advance(x, r, w);
			const int64_t N = int64_t(std::min(w, x + r + 1) - std::max(0, x - r)) * rows;
			// q = (sA I / 2^16 + sB / 2^8) / N, rounded; the sums' true values
			// fit int32.
			const int64_t num = int64_t(int32_t(window.sums[0])) * g[x] + int64_t(int32_t(window.sums[1])) * 256;
			const int64_t q = roundedQuotient(num, 16, N, byCount_[size_t(N)]);
			o[x] = uint8_t(std::clamp<int64_t>(q, 0, 255));
			changed_ += o[x] != pRow[x];
		}
	}
}

void GuidedFilter::filter(const RgbImage &colour, const Gray8Image &matte, const Roi &roi, Gray8Image &out)
{
	const int W = colour.width(), H = colour.height();
	out.resize(W, H);
	changed_ = 0;
	if (roi.empty())
		return;
	const int h = roi.y1 - roi.y0, r = radius_;
	guide_.resize(W, H);
	near_.resize(W, H);
	// Sized for the whole width and the largest radius once, so that no
	// frame allocates whatever the ROI.
	for (auto *s : { &colI_, &colP_, &colII_, &colIP_, &colA_, &colB_ })
		if (s->size() < size_t(W))
			s->resize(size_t(W));
	for (auto *rows : { &momentRow_, &ringRow_ }) {
		if (rows->size() < size_t(W))
			rows->resize(size_t(W));
		std::fill(rows->begin(), rows->end(), INT_MIN); // no column holds a window
	}
	if (zeroBytes_.size() < size_t(W)) {
		zeroBytes_.resize(size_t(W));
		zeroWords_.resize(size_t(W));
	}
	const size_t stride = size_t(W + 7) & ~size_t(7);
	if (reach_.size() < stride)
		reach_.resize(stride);
	if (alongRows_.size() < size_t(4 * kMaxRadius + 3) * stride)
		alongRows_.resize(size_t(4 * kMaxRadius + 3) * stride);
	const size_t ring = size_t(2 * kMaxRadius + 2) * W;
	if (a_.size() < ring) {
		a_.resize(ring);
		b_.resize(ring);
	}

	// Luma (r + 2g + b) / 4, and the pixels near an edge of the matte.
	for (int y = roi.y0; y < roi.y1; ++y)
		luma_(colour.row(y) + roi.x0, roi.x1 - roi.x0, guide_.row(y) + roi.x0);
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

} // namespace depthkey
