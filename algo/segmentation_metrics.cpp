#include "algo/segmentation_metrics.hpp"

#include <cstring>

namespace depthkey {

namespace {

constexpr uint8_t kLecturer = 128;

} // namespace

SegmentationScorer::SegmentationScorer(int tolerancePx)
{
	for (int dy = -tolerancePx; dy <= tolerancePx; ++dy)
		for (int dx = -tolerancePx; dx <= tolerancePx; ++dx)
			if (dx * dx + dy * dy <= tolerancePx * tolerancePx)
				disc_.push_back({ dx, dy });
}

// Row by row with plain pointers (the daemon scores every frame it
// publishes, issue 29): a pixel is an edge when it is inside and a
// 4-neighbour is not. Beyond the image border there is no neighbour: the
// rows above the first and below the last read a row that is all inside,
// and the first and last columns are done apart, so the inner loop has no
// branch and the compiler vectorises it.
void SegmentationScorer::boundary(const Gray8Image &mask, Gray8Image &out)
{
	const int w = mask.width(), h = mask.height();
	out.resize(w, h);
	if (w == 0)
		return;
	if (allInside_.size() != size_t(w))
		allInside_.assign(size_t(w), 255); // once per width
	for (int y = 0; y < h; ++y) {
		const uint8_t *c = mask.row(y);
		const uint8_t *u = y > 0 ? mask.row(y - 1) : allInside_.data();
		const uint8_t *d = y + 1 < h ? mask.row(y + 1) : allInside_.data();
		uint8_t *o = out.row(y);
		for (int x = 1; x < w - 1; ++x)
			o[x] = uint8_t((c[x] >= kLecturer) & ((u[x] < kLecturer) | (d[x] < kLecturer) |
							   (c[x - 1] < kLecturer) | (c[x + 1] < kLecturer)));
		for (int x : { 0, w - 1 }) { // the same pixel twice when w == 1
			const bool left = x > 0 && c[x - 1] < kLecturer, right = x + 1 < w && c[x + 1] < kLecturer;
			o[x] = uint8_t(c[x] >= kLecturer && (u[x] < kLecturer || d[x] < kLecturer || left || right));
		}
	}
}

// Only the edge pixels are looked at (a few thousand of a frame's 300k):
// each row is searched for its next edge eight pixels at a time, then the
// tolerance disc around it.
std::pair<long, long> SegmentationScorer::matched(const Gray8Image &from, const Gray8Image &to) const
{
	const int w = from.width(), h = from.height();
	long hits = 0, total = 0;
	for (int y = 0; y < h; ++y) {
		const uint8_t *row = from.row(y);
		for (int x = 0; x < w; ++x) {
			uint64_t eight;
			if (x + 8 <= w && (std::memcpy(&eight, row + x, 8), eight == 0)) {
				x += 7; // eight pixels without an edge
				continue;
			}
			if (!row[x])
				continue;
			total++;
			for (auto [dx, dy] : disc_) {
				int nx = x + dx, ny = y + dy;
				if (nx >= 0 && ny >= 0 && nx < w && ny < h && to.at(nx, ny)) {
					hits++;
					break;
				}
			}
		}
	}
	return { hits, total };
}

SegmentationScore SegmentationScorer::score(const Gray8Image &predicted, const Gray8Image &truth)
{
	SegmentationScore s;
	if (predicted.width() != truth.width() || predicted.height() != truth.height()) {
		s.fnr = s.fpr = 1;
		return s;
	}
	// Per row in 32-bit counters (a row is far below 2^31 pixels), summed in
	// 64 bits; the rest follows from three counts.
	long both = 0, predictedCount = 0, truthCount = 0;
	for (int y = 0; y < truth.height(); ++y) {
		const uint8_t *p = predicted.row(y), *t = truth.row(y);
		int rowBoth = 0, rowPredicted = 0, rowTruth = 0;
		for (int x = 0; x < truth.width(); ++x) {
			const int pi = p[x] >= kLecturer, ti = t[x] >= kLecturer;
			rowBoth += pi & ti;
			rowPredicted += pi;
			rowTruth += ti;
		}
		both += rowBoth;
		predictedCount += rowPredicted;
		truthCount += rowTruth;
	}
	const long either = predictedCount + truthCount - both;
	const long lost = truthCount - both, taken = predictedCount - both;
	long board = static_cast<long>(truth.size()) - truthCount;
	s.iou = either ? double(both) / either : 1.0;
	s.fnr = truthCount ? double(lost) / truthCount : 0.0;
	s.fpr = board ? double(taken) / board : 0.0;

	boundary(predicted, predictedEdge_);
	boundary(truth, truthEdge_);
	auto [pHits, pTotal] = matched(predictedEdge_, truthEdge_);
	auto [tHits, tTotal] = matched(truthEdge_, predictedEdge_);
	if (pTotal == 0 && tTotal == 0) {
		s.boundaryPrecision = s.boundaryRecall = s.boundaryF = 1.0;
		return s;
	}
	s.boundaryPrecision = pTotal ? double(pHits) / pTotal : 0.0;
	s.boundaryRecall = tTotal ? double(tHits) / tTotal : 0.0;
	double sum = s.boundaryPrecision + s.boundaryRecall;
	s.boundaryF = sum > 0 ? 2 * s.boundaryPrecision * s.boundaryRecall / sum : 0.0;
	return s;
}

void ScoreAverage::add(const SegmentationScore &s)
{
	sum_.iou += s.iou;
	sum_.fnr += s.fnr;
	sum_.fpr += s.fpr;
	sum_.boundaryPrecision += s.boundaryPrecision;
	sum_.boundaryRecall += s.boundaryRecall;
	sum_.boundaryF += s.boundaryF;
	frames_++;
}

SegmentationScore ScoreAverage::mean() const
{
	SegmentationScore m;
	if (!frames_)
		return m;
	double n = static_cast<double>(frames_);
	m.iou = sum_.iou / n;
	m.fnr = sum_.fnr / n;
	m.fpr = sum_.fpr / n;
	m.boundaryPrecision = sum_.boundaryPrecision / n;
	m.boundaryRecall = sum_.boundaryRecall / n;
	m.boundaryF = sum_.boundaryF / n;
	return m;
}

} // namespace depthkey
