// The composite stream at a constant rate in capture time (issue 29 point
// 5): a recorder, a virtual webcam or a player that assumes the frame rate
// must see one frame per colour frame interval, or a recording plays fast
// wherever frames were shed (the keying worker behind) or keyed late. The
// slots between two published frames' capture times that went without one
// are filled with the previous output again, flagged repeated.
// Pure: times are handed in.
#pragma once

#include <cstdint>

namespace depthkey {

// How many capture slots of intervalNs lie strictly between the frames
// captured at previousNs and nowNs (rounded: a camera's capture times
// jitter), 0 when none or when the gap is longer than maxGapNs: an outage,
// not a hiccup (NO SIGNAL frames, not copies, cover it).
constexpr uint64_t skippedCaptureSlots(uint64_t previousNs, uint64_t nowNs, uint64_t intervalNs,
				       uint64_t maxGapNs)
{
	if (previousNs == 0 || nowNs <= previousNs || intervalNs == 0 || nowNs - previousNs > maxGapNs)
		return 0;
	const uint64_t slots = (nowNs - previousNs + intervalNs / 2) / intervalNs;
	return slots > 1 ? slots - 1 : 0;
}

// The slots of a stream in capture time, frame after frame. Slots are
// counted from the previous slot, not from the previous frame's jittered
// capture time, so that the frames written (real and repeated) between two
// captures always number the slots between them: per-gap rounding would
// add a slot now and then under jitter (2% more frames measured with 10 ms
// jitter at 50 fps). A camera whose rate is not quite the nominal one
// re-anchors the slots to its capture time when they drift half a slot off.
class CaptureSlotClock
{
public:
	void configure(uint64_t intervalNs, uint64_t maxGapNs)
	{
		intervalNs_ = intervalNs;
		maxGapNs_ = maxGapNs;
		reset();
	}
	void reset() { slotNs_ = previousNs_ = 0; }

	// A frame captured at ns: how many slots before its own went without a
	// frame (fill them at slotNs(1..n)); then the clock is at its slot.
	uint64_t skippedBefore(uint64_t ns)
	{
		previousNs_ = slotNs_;
		const uint64_t skipped = skippedCaptureSlots(slotNs_, ns, intervalNs_, maxGapNs_);
		if (slotNs_ != 0 && ns > slotNs_)
			slotNs_ += (skipped + 1) * intervalNs_;
		const uint64_t off = slotNs_ > ns ? slotNs_ - ns : ns - slotNs_;
		if (slotNs_ == 0 || 2 * off > intervalNs_)
			slotNs_ = ns; // the first frame, an outage, or drift: the camera's time
		return skipped;
	}
	// The capture time of the k-th skipped slot (k >= 1) before the frame
	// last given to skippedBefore().
	uint64_t slotNs(uint64_t k) const { return previousNs_ + k * intervalNs_; }
	uint64_t intervalNs() const { return intervalNs_; }

private:
	uint64_t intervalNs_ = 0, maxGapNs_ = 0;
	uint64_t slotNs_ = 0;     // the slot of the last frame, 0 none
	uint64_t previousNs_ = 0; // slotNs_ before the last skippedBefore()
};

} // namespace depthkey
