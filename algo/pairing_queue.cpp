#include "algo/pairing_queue.hpp"

#include <algorithm>
#include <utility>

namespace depthkey {

void PairingQueue::configure(int64_t offsetNs, uint64_t maxSkewNs, uint64_t delayNs, size_t slots)
{
	maxSkewNs_ = maxSkewNs;
	pairer_.configure(offsetNs, maxSkewNs);
	delayNs_ = delayNs;
	slots = std::clamp<size_t>(slots, 1, kMaxSlots);
	if (slots != slotCount_) {
		// Held frames keep their order only in a ring of the same size.
		count_ = first_ = 0;
		slotCount_ = slots;
	}
}

size_t PairingQueue::slotsFor(uint64_t delayNs, int colourFps)
{
	// The frames arriving within the delay: the newest and those before it
	// whose delay has not run out (at 150 ms and 40 ms a frame: 0, 40, 80
	// and 120 ms old). Holding them keys each at its time; a frame that
	// comes early (jitter) finds the ring full and keys the oldest a little
	// early (next() with makeRoom), as one more slot did before, which
	// cost a whole frame (0.9 MB at 640x480) for that.
	const uint64_t perFrameNs = 1'000'000'000ull / uint64_t(std::max(1, colourFps));
	return std::clamp<size_t>(size_t(delayNs / perFrameNs) + 1, 1, kMaxSlots);
}

void PairingQueue::clear()
{
	pairer_.clear();
	count_ = first_ = 0;
}

void PairingQueue::addColour(const ColourFrame &frame, uint64_t nowNs)
{
	if (count_ == slotCount_)
		pop(); // full: the caller did not make room (next() with makeRoom); it is lost
	Slot &slot = slots_[(first_ + count_) % slotCount_];
	if (&slot.frame != &frame) // made elsewhere, not in freeSlot()
		slot.frame = frame; // same size: the vector reuses its storage
	slot.deadlineNs = nowNs + delayNs_;
	count_++;
}

ColourFrame *PairingQueue::freeSlot()
{
	if (count_ == slotCount_)
		return nullptr;
	return &slots_[(first_ + count_) % slotCount_].frame;
}

bool PairingQueue::due(const Slot &slot, uint64_t nowNs, bool makeRoom) const
{
	return (makeRoom && count_ == slotCount_) || nowNs >= slot.deadlineNs;
}

bool PairingQueue::next(uint64_t nowNs, Keying &out, bool makeRoom)
{
	if (!count_ || !due(slots_[first_], nowNs, makeRoom))
		return false;
	out.colour = &slots_[first_].frame;
	out.depth = pairer_.bracket(out.colour->timestampNs);
	return true;
}

void PairingQueue::pop()
{
	if (!count_)
		return;
	first_ = (first_ + 1) % slotCount_;
	count_--;
}

void PairingQueue::popInto(ColourFrame &out)
{
	if (!count_)
		return;
	std::swap(out, slots_[first_].frame);
	pop();
}

uint64_t PairingQueue::nextDeadlineNs() const
{
	return count_ ? slots_[first_].deadlineNs : 0;
}

} // namespace depthkey
