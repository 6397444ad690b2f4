// Colour frames held back until depth from both sides of them in time is in
// (pairing.delay_ms). The depth camera runs slower than the colour camera and
// its frames arrive late (latency), so keying a colour frame at once means
// keying it with depth captured 40-150 ms before it: a walking lecturer has
// moved 10-50 px since. Waiting up to about one depth period plus the depth
// latency lets each colour frame be keyed with the depth frame captured just
// before it and the one just after it (FramePairer::bracket).
//
// A held frame is due when it has waited delay_ms since it arrived, or when
// the ring is full and another frame is about to come (a colour camera
// faster than configured); it is then keyed with the depth frames around its
// capture that have come by then. The ring holds the frames that arrive
// within one delay and no more (4 at 150 ms, 25 fps): a frame that leaves
// is keyed elsewhere (the daemon's keying worker takes it by popInto()), so
// it needs no slot here, and the room a new frame needs is made before it
// is added (next() with makeRoom) rather than by a spare slot. A constant
// delay, rather than leaving as soon as the later depth frame is
// in, keeps the output as even as the input: a recorder or a virtual webcam
// sees 25 frames a second, not a burst of three each time a depth frame
// arrives. Frames leave in arrival order with their own capture
// timestamps. The queue waits on nothing but time: without a depth camera
// every frame leaves after the delay, unpaired. delay 0 keys every frame as
// it arrives (lowest latency).
//
// The ring's frames are allocated once at their size; pushing a frame of the
// same size copies into storage that is already there. Pure: times are
// handed in.
#pragma once

#include "algo/frame_pairer.hpp"
#include "algo/frames.hpp"

#include <array>
#include <cstdint>

namespace depthkey {

class PairingQueue
{
public:
	static constexpr size_t kMaxSlots = 16;

	// slots: frames held at most (1..kMaxSlots); slotsFor() gives what a
	// delay needs at a frame rate: the frames that arrive within it.
	void configure(int64_t offsetNs, uint64_t maxSkewNs, uint64_t delayNs, size_t slots);
	static size_t slotsFor(uint64_t delayNs, int colourFps);
	void setOffset(int64_t offsetNs) { pairer_.configure(offsetNs, maxSkewNs_); }
	// Forgets held colour and depth frames (a camera restarted).
	void clear();

	void addDepth(const DepthFrame &frame) { pairer_.addDepth(frame); }
	void addColour(const ColourFrame &frame, uint64_t nowNs);
	// The slot the next addColour() fills, for a camera to make its frame in
	// (Camera::lendFrames): addColour() of that very frame copies nothing.
	// Null when the ring is full. Valid until addColour(), clear() or
	// configure(); pop() and next() do not move it. No member reads or
	// writes that frame before addColour() takes it (the storage of all
	// slots stays put), so a camera may fill it on a thread of its own
	// while the queue is used on another.
	ColourFrame *freeSlot();

	// The oldest held frame when it is due at nowNs, bracketed with depth;
	// false when none is due. makeRoom: a colour frame is about to be
	// added, so a full ring's oldest frame is due too (keyed early rather
	// than lost). Valid until pop(), addColour() or addDepth().
	struct Keying {
		const ColourFrame *colour = nullptr;
		FramePairer::Bracket depth;
	};
	bool next(uint64_t nowNs, Keying &out, bool makeRoom = false);
	void pop();
	// pop() that hands the oldest frame over by swap: out gets it, the ring
	// keeps out's old storage for a later frame (no copy, and no allocation
	// once the sizes agree). For a frame keyed on another thread (issue 28).
	void popInto(ColourFrame &out);

	size_t held() const { return count_; }
	// When the oldest held frame falls due by time alone; 0 when none is held.
	uint64_t nextDeadlineNs() const;
	const FramePairer &pairer() const { return pairer_; }

private:
	struct Slot {
		ColourFrame frame;
		uint64_t deadlineNs = 0;
	};
	bool due(const Slot &slot, uint64_t nowNs, bool makeRoom) const;

	FramePairer pairer_;
	std::array<Slot, kMaxSlots> slots_;
	size_t slotCount_ = 1, first_ = 0, count_ = 0;
	uint64_t delayNs_ = 0, maxSkewNs_ = 150'000'000;
};

} // namespace depthkey
