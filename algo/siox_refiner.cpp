#include "algo/siox_refiner.hpp"

#include "algo/quantised_colour.hpp"

#include <algorithm>
#include <cstring>

namespace depthkey {

namespace {

// Temporary marks inside work_ while flooding; seeds are only ever 0 or 255.
constexpr uint8_t kUnreachedLecturer = 1;
constexpr uint8_t kUnreachedBoard = 2;

} // namespace

void SioxRefiner::refine(const RgbImage &colour, const Gray8Image &trimap, const Roi &roi,
			 SioxClassifier &classifier, Gray8Image &alpha)
{
	width_ = colour.width();
	height_ = colour.height();
	alpha.resize(width_, height_);
	std::memset(alpha.data(), 0, alpha.size());
	work_.resize(width_, height_);
	band_.clear();
	if (roi.empty() || trimap.width() != width_ || trimap.height() != height_)
		return;
	collectAndClassify(colour, trimap, roi, classifier);
	if (settings_.smoothing > 0)
		smooth();
	keepComponentsTouchingLecturer();
	fillHoles();
	writeAlpha(roi, alpha);
}

void SioxRefiner::collectAndClassify(const RgbImage &colour, const Gray8Image &trimap, const Roi &roi,
				     SioxClassifier &classifier)
{
	if (band_.capacity() < work_.size()) {
		// Grows only when the image grows; steady state never gets here.
		band_.reserve(work_.size());
		colourConfidence_.reserve(work_.size());
		next_.reserve(work_.size());
		stack_.reserve(work_.size());
	}
	colourConfidence_.clear();
	for (int y = roi.y0; y < roi.y1; ++y) {
		const uint8_t *t = trimap.row(y);
		const Rgb8 *c = colour.row(y);
		uint8_t *w = work_.row(y);
		for (int x = roi.x0; x < roi.x1; ++x) {
			uint8_t label = t[x];
			if (label == kTrimapBoard || label == kTrimapLecturer) {
				w[x] = label;
				continue;
			}
			uint8_t conf = classifier.confidence(quantiseColour(c[x]));
			band_.push_back(y * width_ + x);
			colourConfidence_.push_back(conf);
			w[x] = conf >= kConfidenceLecturer ? 255 : 0;
		}
	}
}

void SioxRefiner::smooth()
{
	const int w = width_, h = height_;
	uint8_t *m = work_.data();
	next_.resize(band_.size());
	for (int pass = 0; pass < settings_.smoothing; ++pass) {
		for (size_t k = 0; k < band_.size(); ++k) {
			int p = band_[k], x = p % w, y = p / w;
			int x0 = std::max(0, x - 1), x1 = std::min(w - 1, x + 1);
			int y0 = std::max(0, y - 1), y1 = std::min(h - 1, y + 1);
			unsigned sum = 0, count = 0;
			for (int yy = y0; yy <= y1; ++yy)
				for (int xx = x0; xx <= x1; ++xx, ++count)
					sum += m[yy * w + xx];
			// Interior: sum / 9 as (sum * 7282 + 32768) >> 16 (7282 = 2^16 / 9,
			// exact for sums up to 9 * 255); at the image border a true division.
			next_[k] = uint8_t(count == 9 ? (sum * 7282u + 32768u) >> 16 : (sum + count / 2) / count);
		}
		for (size_t k = 0; k < band_.size(); ++k)
			m[band_[k]] = next_[k];
	}
	for (int p : band_)
		m[p] = m[p] >= 128 ? 255 : 0;
}

void SioxRefiner::keepComponentsTouchingLecturer()
{
	const int w = width_, n = width_ * height_;
	uint8_t *m = work_.data();
	for (int p : band_)
		if (m[p])
			m[p] = kUnreachedLecturer;
	auto touches = [&](int p, uint8_t value) {
		int x = p % w;
		return (x > 0 && m[p - 1] == value) || (x + 1 < w && m[p + 1] == value) ||
		       (p >= w && m[p - w] == value) || (p + w < n && m[p + w] == value);
	};
	size_t top = 0;
	stack_.resize(band_.size());
	for (int p : band_) {
		if (m[p] == kUnreachedLecturer && touches(p, 255)) {
			m[p] = 255;
			stack_[top++] = p;
		}
	}
	while (top) {
		int p = stack_[--top], x = p % w;
		auto visit = [&](int q) {
			if (m[q] == kUnreachedLecturer) {
				m[q] = 255;
				stack_[top++] = q;
			}
		};
		if (x > 0)
			visit(p - 1);
		if (x + 1 < w)
			visit(p + 1);
		if (p >= w)
			visit(p - w);
		if (p + w < n)
			visit(p + w);
	}
	for (int p : band_)
		if (m[p] == kUnreachedLecturer)
			m[p] = 0;
}

void SioxRefiner::fillHoles()
{
	const int w = width_, h = height_, n = width_ * height_;
	uint8_t *m = work_.data();
	for (int p : band_)
		if (!m[p])
			m[p] = kUnreachedBoard;
	size_t top = 0;
	for (int p : band_) {
		if (m[p] != kUnreachedBoard)
			continue;
		int x = p % w, y = p / w;
		bool border = x == 0 || y == 0 || x == w - 1 || y == h - 1;
		bool nextToBoard = (x > 0 && m[p - 1] == 0) || (x + 1 < w && m[p + 1] == 0) ||
				   (p >= w && m[p - w] == 0) || (p + w < n && m[p + w] == 0);
		if (border || nextToBoard) {
			m[p] = 0;
			stack_[top++] = p;
		}
	}
	while (top) {
		int p = stack_[--top], x = p % w;
		auto visit = [&](int q) {
			if (m[q] == kUnreachedBoard) {
				m[q] = 0;
				stack_[top++] = q;
			}
		};
		if (x > 0)
			visit(p - 1);
		if (x + 1 < w)
			visit(p + 1);
		if (p >= w)
			visit(p - w);
		if (p + w < n)
			visit(p + w);
	}
	for (int p : band_)
		if (m[p] == kUnreachedBoard)
			m[p] = 255;
}

void SioxRefiner::writeAlpha(const Roi &roi, Gray8Image &alpha) const
{
	for (int y = roi.y0; y < roi.y1; ++y)
		std::memcpy(alpha.row(y) + roi.x0, work_.row(y) + roi.x0, size_t(roi.x1 - roi.x0));
	if (!settings_.softAlpha)
		return;
	const int w = width_, n = width_ * height_;
	const uint8_t *m = work_.data();
	uint8_t *a = alpha.data();
	for (size_t k = 0; k < band_.size(); ++k) {
		int p = band_[k], x = p % w;
		uint8_t v = m[p];
		bool edge = (x > 0 && m[p - 1] != v) || (x + 1 < w && m[p + 1] != v) ||
			    (p >= w && m[p - w] != v) || (p + w < n && m[p + w] != v);
		if (!edge)
			continue;
		uint8_t c = colourConfidence_[k];
		a[p] = v ? std::max<uint8_t>(c, kConfidenceLecturer) : std::min<uint8_t>(c, kConfidenceLecturer - 1);
	}
}

} // namespace depthkey
