#include "algo/live_score.hpp"

#include <algorithm>

namespace depthkey {

void LiveScore::add(const Gray8Image &lecturer, const Gray8Image &truth, uint64_t captureNs)
{
	if (truth.empty())
		return;
	record(scorer_.score(lecturer, truth), captureNs);
	lastLayer_ = lecturer; // same size: the vector reuses its storage
}

void LiveScore::addWithoutLecturer(const Gray8Image &truth, uint64_t captureNs)
{
	if (truth.empty())
		return;
	if (blank_.width() != truth.width() || blank_.height() != truth.height())
		blank_ = Gray8Image(truth.width(), truth.height(), 0); // once per frame size
	record(scorer_.score(blank_, truth), captureNs);
	lastLayer_ = blank_;
}

void LiveScore::addRepeated(const Gray8Image &truth, uint64_t captureNs)
{
	if (truth.empty() || lastLayer_.empty())
		return;
	record(scorer_.score(lastLayer_, truth), captureNs);
}

void LiveScore::record(const SegmentationScore &s, uint64_t captureNs)
{
	ring_[next_] = { captureNs, s.iou, s.boundaryF };
	next_ = (next_ + 1) % ring_.size();
	held_ = std::min(held_ + 1, ring_.size());
	newestNs_ = std::max(newestNs_, captureNs);
	total_.frames++;
	iouSum_ += s.iou;
	boundaryFSum_ += s.boundaryF;
}

LiveScoreFigures LiveScore::recent() const
{
	LiveScoreFigures f;
	double iou = 0, bf = 0;
	for (size_t k = 0; k < held_; ++k) {
		const Entry &e = ring_[(next_ + ring_.size() - 1 - k) % ring_.size()];
		if (e.captureNs + kWindowNs <= newestNs_)
			continue; // older than the window (a repeated frame may stand for an earlier time)
		f.frames++;
		iou += e.iou;
		bf += e.boundaryF;
	}
	if (f.frames) {
		f.iou = iou / double(f.frames);
		f.boundaryF = bf / double(f.frames);
	}
	return f;
}

LiveScoreFigures LiveScore::sinceStart() const
{
	LiveScoreFigures f = total_;
	if (f.frames) {
		f.iou = iouSum_ / double(f.frames);
		f.boundaryF = boundaryFSum_ / double(f.frames);
	}
	return f;
}

void LiveScore::reset()
{
	held_ = next_ = 0;
	lastLayer_ = Gray8Image{};
	newestNs_ = 0;
	total_ = {};
	iouSum_ = boundaryFSum_ = 0;
}

} // namespace depthkey
