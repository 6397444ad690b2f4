#include "algo/frame_pairer.hpp"

#include <algorithm>

namespace depthkey {

PairableOffsets pairableOffsetsMs(int maxSkewMs, int delayMs, int colourFps, int depthFps)
{
	// Rates are 1..60 (config); guarded so a zero cannot divide.
	const int colourPeriodMs = 1000 / (colourFps > 0 ? colourFps : 1);
	const int historyMs = static_cast<int>(FramePairer::kHistory) * 1000 / (depthFps > 0 ? depthFps : 1);
	return { -(delayMs + maxSkewMs + colourPeriodMs), historyMs + maxSkewMs };
}

void FramePairer::configure(int64_t offsetNs, uint64_t maxSkewNs)
{
	offsetNs_ = offsetNs;
	maxSkewNs_ = maxSkewNs;
}

void FramePairer::clear()
{
	for (size_t i = 0; i < count_; i++)
		slots_[i].used = false;
	count_ = 0;
	next_ = 0;
}

int64_t FramePairer::corrected(const DepthFrame &frame) const
{
	return static_cast<int64_t>(frame.timestampNs) + offsetNs_;
}

void FramePairer::addDepth(const DepthFrame &frame)
{
	const DepthFrame *last = newest();
	if (last && frame.timestampNs <= last->timestampNs) {
		stats_.depthOutOfOrder++;
		return;
	}
	Slot &slot = slots_[next_];
	if (count_ == kHistory && !slot.used)
		stats_.depthUnused++;
	slot.frame = frame; // same size: the vectors reuse their storage
	slot.used = false;
	next_ = (next_ + 1) % kHistory;
	if (count_ < kHistory)
		count_++;
}

const DepthFrame *FramePairer::match(uint64_t colourNs)
{
	Slot *best = nullptr;
	uint64_t bestSkew = 0;
	for (size_t i = 0; i < count_; i++) {
		int64_t d = corrected(slots_[i].frame) - static_cast<int64_t>(colourNs);
		uint64_t skew = static_cast<uint64_t>(d < 0 ? -d : d);
		if (!best || skew < bestSkew) {
			best = &slots_[i];
			bestSkew = skew;
		}
	}
	if (!best || bestSkew > maxSkewNs_) {
		stats_.unpaired++;
		return nullptr;
	}
	best->used = true;
	stats_.paired++;
	return &best->frame;
}

FramePairer::Bracket FramePairer::bracket(uint64_t colourNs)
{
	Bracket b;
	Slot *before = nullptr, *after = nullptr;
	const int64_t c = static_cast<int64_t>(colourNs), skew = static_cast<int64_t>(maxSkewNs_);
	for (size_t i = 0; i < count_; i++) {
		const int64_t t = corrected(slots_[i].frame);
		if (t <= c && c - t <= skew && (!before || t > b.beforeNs)) {
			before = &slots_[i];
			b.beforeNs = t;
		} else if (t > c && t - c <= skew && (!after || t < b.afterNs)) {
			after = &slots_[i];
			b.afterNs = t;
		}
	}
	for (Slot *s : { before, after })
		if (s) {
			s->used = true;
		}
	if (!before && !after)
		return nearestWithin(c, kLostNs);
	b.before = before ? &before->frame : nullptr;
	b.after = after ? &after->frame : nullptr;
	stats_.paired++;
	return b;
}

FramePairer::Bracket FramePairer::nearestWithin(int64_t colourNs, int64_t limitNs)
{
	Bracket b;
	Slot *best = nullptr;
	int64_t bestNs = 0, bestGap = 0;
	for (size_t i = 0; i < count_; i++) {
		const int64_t t = corrected(slots_[i].frame), gap = t > colourNs ? t - colourNs : colourNs - t;
		if (gap <= limitNs && (!best || gap < bestGap)) {
			best = &slots_[i];
			bestNs = t;
			bestGap = gap;
		}
	}
	if (!best) {
		stats_.unpaired++;
		return b;
	}
	best->used = true;
	stats_.stale++;
	b.staleNs = std::max<int64_t>(1, bestGap);
	if (bestNs <= colourNs) {
		b.before = &best->frame;
		b.beforeNs = bestNs;
	} else {
		b.after = &best->frame;
		b.afterNs = bestNs;
	}
	return b;
}

const DepthFrame *FramePairer::newest() const
{
	if (count_ == 0)
		return nullptr;
	return &slots_[(next_ + kHistory - 1) % kHistory].frame;
}

bool FramePairer::newestNs(int64_t &ns) const
{
	const DepthFrame *frame = newest();
	if (frame)
		ns = corrected(*frame);
	return frame != nullptr;
}

} // namespace depthkey
