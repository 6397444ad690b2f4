#include "algo/segmentation_metrics.hpp"

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

void SegmentationScorer::boundary(const Gray8Image &mask, Gray8Image &out) const
{
	const int w = mask.width(), h = mask.height();
	out.resize(w, h);
	for (int y = 0; y < h; ++y)
		for (int x = 0; x < w; ++x) {
			bool inside = mask.at(x, y) >= kLecturer;
			bool edge = inside && ((x > 0 && mask.at(x - 1, y) < kLecturer) ||
					       (x + 1 < w && mask.at(x + 1, y) < kLecturer) ||
					       (y > 0 && mask.at(x, y - 1) < kLecturer) ||
					       (y + 1 < h && mask.at(x, y + 1) < kLecturer));
			out.at(x, y) = edge ? 1 : 0;
		}
}

std::pair<long, long> SegmentationScorer::matched(const Gray8Image &from, const Gray8Image &to) const
{
	const int w = from.width(), h = from.height();
	long hits = 0, total = 0;
	for (int y = 0; y < h; ++y)
		for (int x = 0; x < w; ++x) {
			if (!from.at(x, y))
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
	return { hits, total };
}

SegmentationScore SegmentationScorer::score(const Gray8Image &predicted, const Gray8Image &truth)
{
	SegmentationScore s;
	if (predicted.width() != truth.width() || predicted.height() != truth.height()) {
		s.fnr = s.fpr = 1;
		return s;
	}
	long both = 0, either = 0, truthCount = 0, lost = 0, taken = 0;
	for (size_t i = 0; i < truth.size(); ++i) {
		bool p = predicted.data()[i] >= kLecturer, t = truth.data()[i] >= kLecturer;
		both += p && t;
		either += p || t;
		truthCount += t;
		lost += t && !p;
		taken += p && !t;
	}
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
