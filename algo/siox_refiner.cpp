#include "algo/siox_refiner.hpp"

#include "algo/band_scan.hpp"
#include "algo/quantised_colour.hpp"

#include <algorithm>
#include <cstring>

namespace depthkey {

void SioxRefiner::refine(const RgbImage &colour, const Gray8Image &trimap, const Roi &roi, BandEvidence &evidence,
			 Gray8Image &alpha)
{
	if (colour.width() != width_ || colour.height() != height_ || work_.empty()) {
		width_ = colour.width();
		height_ = colour.height();
		stride_ = width_ + 2;
		work_.resize(stride_, height_ + 2);
		std::memset(work_.data(), kBandOutside, work_.size());
		const size_t pixels = size_t(width_) * height_;
		// Grows only when the image grows; steady state never gets here.
		spans_.reserve(size_t(width_ / 2 + 1) * height_);
		colourConfidence_.reserve(pixels);
		next_.reserve(pixels);
		components_.reserve(pixels);
	}
	alpha.resize(width_, height_);
	std::memset(alpha.data(), 0, alpha.size());
	spans_.clear();
	bandPixels_ = 0;
	if (roi.empty() || trimap.width() != width_ || trimap.height() != height_)
		return;
	collectAndClassify(trimap, roi, evidence);
	if (cut_.enabled() && bandPixels_ <= cutMaxBandPixels_)
		decideByCut(colour, trimap);
	else if (settings_.smoothing > 0)
		smooth();
	const size_t minKeep = std::max(kFreeComponentMinPx, size_t(width_) * size_t(height_) / kFreeComponentDivisor);
	components_.keepTouchingLecturer(work_.data(), stride_, spans_, lecturerBeyondBorder_, minKeep);
	components_.fillHoles(work_.data(), stride_, spans_, colourConfidence_.data(), kClearlyBoard);
	writeAlpha(roi, alpha);
}

void SioxRefiner::collectAndClassify(const Gray8Image &trimap, const Roi &roi, BandEvidence &evidence)
{
	colourConfidence_.clear();
	const BandScanFn nextUndecided = bandScanRow(kernelPath_); // once per image
	for (int y = roi.y0; y < roi.y1; ++y) {
		const uint8_t *t = trimap.row(y);
		uint8_t *w = work_.data() + at(0, y);
		std::memcpy(w + roi.x0, t + roi.x0, size_t(roi.x1 - roi.x0));
		for (int x = nextUndecided(t, roi.x0, roi.x1); x < roi.x1; x = nextUndecided(t, x, roi.x1)) {
			Span span{ y, x, x, int(colourConfidence_.size()) };
			while (x < roi.x1 && !isTrimapSeed(t[x]))
				++x;
			span.x1 = x;
			// Within the capacity reserved for the whole image: no allocation.
			colourConfidence_.resize(colourConfidence_.size() + size_t(span.x1 - span.x0));
			uint8_t *conf = colourConfidence_.data() + span.first;
			evidence.confidences(y, span.x0, span.x1, conf);
			for (int k = 0; k < span.x1 - span.x0; ++k)
				w[span.x0 + k] = conf[k] >= kConfidenceLecturer ? 255 : 0;
			spans_.push_back(span);
		}
	}
	bandPixels_ = colourConfidence_.size();
}

void SioxRefiner::decideByCut(const RgbImage &colour, const Gray8Image &trimap)
{
	next_.resize(bandPixels_); // within the capacity reserved for the image
	cut_.cut(colour, trimap, spans_, colourConfidence_.data(), next_.data());
	uint8_t *m = work_.data();
	forEachBandPixel([&](int p, int k) { m[p] = next_[k]; });
}

void SioxRefiner::smooth()
{
	const int w = width_, h = height_, stride = stride_;
	uint8_t *m = work_.data();
	next_.resize(bandPixels_);
	for (int pass = 0; pass < settings_.smoothing; ++pass) {
		for (const Span &s : spans_) {
			uint8_t *out = next_.data() + s.first;
			if (s.y > 0 && s.y + 1 < h && s.x0 > 0 && s.x1 < w) {
				// Interior: sum / 9 as (sum * 7282 + 32768) >> 16 (7282 =
				// 2^16 / 9, exact for sums up to 9 * 255).
				for (int x = s.x0, p = at(s.x0, s.y); x < s.x1; ++x, ++p) {
					const uint8_t *up = m + p - stride, *mid = m + p, *down = m + p + stride;
					unsigned sum = unsigned(up[-1]) + up[0] + up[1] + mid[-1] + mid[0] + mid[1] + down[-1] +
						       down[0] + down[1];
					*out++ = uint8_t((sum * 7282u + 32768u) >> 16);
				}
				continue;
			}
			// At the image border: the mean of the neighbours inside it.
			for (int x = s.x0; x < s.x1; ++x) {
				int x0 = std::max(0, x - 1), x1 = std::min(w - 1, x + 1);
				int y0 = std::max(0, s.y - 1), y1 = std::min(h - 1, s.y + 1);
				unsigned sum = 0, count = 0;
				for (int yy = y0; yy <= y1; ++yy)
					for (int xx = x0; xx <= x1; ++xx, ++count)
						sum += m[at(xx, yy)];
				*out++ = uint8_t((sum + count / 2) / count);
			}
		}
		forEachBandPixel([&](int p, int k) { m[p] = next_[k]; });
	}
	forEachBandPixel([&](int p, int) { m[p] = m[p] >= 128 ? 255 : 0; });
}

void SioxRefiner::writeAlpha(const Roi &roi, Gray8Image &alpha) const
{
	for (int y = roi.y0; y < roi.y1; ++y)
		std::memcpy(alpha.row(y) + roi.x0, work_.data() + at(roi.x0, y), size_t(roi.x1 - roi.x0));
	if (!settings_.softAlpha)
		return;
	const int stride = stride_;
	const uint8_t *m = work_.data();
	for (const Span &s : spans_) {
		uint8_t *a = alpha.row(s.y);
		for (int x = s.x0, p = at(s.x0, s.y), k = s.first; x < s.x1; ++x, ++p, ++k) {
			// An edge: a 4-neighbour inside the image on the other side.
			const uint8_t v = m[p];
			auto differs = [&](uint8_t n) { return n != v && n != kBandOutside; };
			if (!differs(m[p - 1]) && !differs(m[p + 1]) && !differs(m[p - stride]) && !differs(m[p + stride]))
				continue;
			const uint8_t c = colourConfidence_[k];
			a[x] = v ? std::max<uint8_t>(c, kConfidenceLecturer) : std::min<uint8_t>(c, kConfidenceLecturer - 1);
		}
	}
}

} // namespace depthkey
