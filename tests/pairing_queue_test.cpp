// The colour delay line (pairing.delay_ms): frames wait for depth captured
// after them, or for the delay; they leave in order, keep their timestamps,
// and never wait on anything but time.
#include <gtest/gtest.h>

#include "algo/pairing_queue.hpp"

using namespace depthkey;

namespace {

constexpr uint64_t kMs = 1'000'000;

DepthFrame depthStamped(uint64_t ms)
{
	DepthFrame f;
	f.depthMm.resize(2, 1);
	f.depthMm.at(0, 0) = static_cast<uint16_t>(ms);
	f.timestampNs = ms * kMs;
	return f;
}

ColourFrame colourAt(uint64_t ms, uint64_t sequence)
{
	ColourFrame f;
	f.rgb.resize(2, 1);
	f.timestampNs = ms * kMs;
	f.sequence = sequence;
	return f;
}

} // namespace

TEST(PairingQueue, KeysWithDepthFromBothSidesAfterAConstantDelay)
{
	PairingQueue q;
	q.configure(-40 * kMs, 150 * kMs, 150 * kMs, PairingQueue::slotsFor(150 * kMs, 25));
	q.addDepth(depthStamped(1040)); // captured 1000
	q.addColour(colourAt(1020, 1), 1020 * kMs);
	q.addColour(colourAt(1060, 2), 1060 * kMs);
	PairingQueue::Keying k;
	EXPECT_FALSE(q.next(1100 * kMs, k));
	q.addDepth(depthStamped(1140));        // captured 1100: after both
	EXPECT_FALSE(q.next(1140 * kMs, k));   // in, but the frame leaves at its time
	ASSERT_TRUE(q.next(1170 * kMs, k));
	EXPECT_EQ(k.colour->sequence, 1u);
	EXPECT_EQ(k.colour->timestampNs, 1020 * kMs);
	ASSERT_TRUE(k.depth.before && k.depth.after);
	EXPECT_EQ(k.depth.before->depthMm.at(0, 0), 1040);
	EXPECT_EQ(k.depth.after->depthMm.at(0, 0), 1140);
	q.pop();
	EXPECT_FALSE(q.next(1170 * kMs, k));   // 40 ms later, as it came
	ASSERT_TRUE(q.next(1210 * kMs, k));
	EXPECT_EQ(k.colour->sequence, 2u);
	q.pop();
	EXPECT_EQ(q.held(), 0u);
	EXPECT_FALSE(q.next(1210 * kMs, k));
}

TEST(PairingQueue, WithoutDepthFramesLeaveAfterTheDelayUnpaired)
{
	PairingQueue q;
	q.configure(0, 150 * kMs, 100 * kMs, PairingQueue::slotsFor(100 * kMs, 25));
	q.addColour(colourAt(1000, 1), 1000 * kMs);
	q.addColour(colourAt(1040, 2), 1040 * kMs);
	EXPECT_EQ(q.nextDeadlineNs(), 1100 * kMs);
	PairingQueue::Keying k;
	EXPECT_FALSE(q.next(1099 * kMs, k));
	ASSERT_TRUE(q.next(1100 * kMs, k));
	EXPECT_EQ(k.colour->sequence, 1u);
	EXPECT_FALSE(k.depth.any());
	q.pop();
	EXPECT_FALSE(q.next(1100 * kMs, k)); // the second waits its own delay
	EXPECT_EQ(q.nextDeadlineNs(), 1140 * kMs);
	EXPECT_EQ(q.pairer().stats().unpaired, 1u);
}

TEST(PairingQueue, ZeroDelayKeysEachFrameAtOnce)
{
	PairingQueue q;
	q.configure(0, 150 * kMs, 0, PairingQueue::slotsFor(0, 25));
	q.addDepth(depthStamped(990));
	q.addColour(colourAt(1000, 7), 1000 * kMs);
	PairingQueue::Keying k;
	ASSERT_TRUE(q.next(1000 * kMs, k));
	EXPECT_EQ(k.colour->sequence, 7u);
	ASSERT_TRUE(k.depth.before);
	EXPECT_EQ(k.depth.before->depthMm.at(0, 0), 990);
	EXPECT_EQ(k.depth.after, nullptr);
}

TEST(PairingQueue, AFullRingLetsTheOldestGoInOrder)
{
	PairingQueue q;
	q.configure(0, 150 * kMs, 1000 * kMs, 3);
	PairingQueue::Keying k;
	for (uint64_t i = 0; i < 3; ++i)
		q.addColour(colourAt(1000 + 40 * i, i), (1000 + 40 * i) * kMs);
	// Full, and a frame is coming: the oldest is due although neither depth
	// nor the delay came. Full with no frame coming, it waits its time.
	EXPECT_FALSE(q.next(1080 * kMs, k));
	ASSERT_TRUE(q.next(1120 * kMs, k, true));
	EXPECT_EQ(k.colour->sequence, 0u);
	q.pop();
	EXPECT_FALSE(q.next(1120 * kMs, k, true));
}

TEST(PairingQueue, HoldsTheFramesOfOneDelayAndKeysEachAtItsTime)
{
	// 150 ms at 25 fps: 0, 40, 80 and 120 ms old are held, 4 frames.
	EXPECT_EQ(PairingQueue::slotsFor(150 * kMs, 25), 4u);
	EXPECT_EQ(PairingQueue::slotsFor(0, 25), 1u);
	PairingQueue q;
	q.configure(0, 150 * kMs, 150 * kMs, PairingQueue::slotsFor(150 * kMs, 25));
	PairingQueue::Keying k;
	uint64_t keyed = 0;
	for (uint64_t i = 0; i < 20; ++i) {
		const uint64_t now = (1000 + 40 * i) * kMs;
		// As the daemon does: what is due, room for the frame, the frame.
		for (uint64_t t = now - 40 * kMs + kMs; t <= now; t += kMs)
			while (q.next(t, k, t == now)) {
				EXPECT_EQ(t, k.colour->timestampNs + 150 * kMs); // never early
				EXPECT_EQ(k.colour->sequence, keyed++);
				q.pop();
			}
		q.addColour(colourAt(1000 + 40 * i, i), now);
	}
	EXPECT_EQ(keyed, 16u);
	EXPECT_EQ(q.held(), 4u);
}

// A camera makes its frame in the slot the next addColour() fills
// (Camera::lendFrames): the held frame is that very storage, not a copy, and
// a full ring lends nothing.
TEST(PairingQueue, AFrameMadeInTheFreeSlotIsHeldWithoutACopy)
{
	PairingQueue q;
	q.configure(0, 150 * kMs, 150 * kMs, 2);
	PairingQueue::Keying k;
	ColourFrame *slot = q.freeSlot();
	ASSERT_NE(slot, nullptr);
	*slot = colourAt(1000, 7);
	const Rgb8 *pixels = slot->rgb.data();
	q.addColour(*slot, 1000 * kMs);
	EXPECT_EQ(q.held(), 1u);
	ColourFrame *second = q.freeSlot();
	ASSERT_NE(second, nullptr);
	EXPECT_NE(second, slot);
	q.addColour(colourAt(1040, 8), 1040 * kMs); // made elsewhere: copied into that slot
	EXPECT_EQ(second->sequence, 8u);
	EXPECT_EQ(q.freeSlot(), nullptr); // full
	ASSERT_TRUE(q.next(1150 * kMs, k));
	EXPECT_EQ(k.colour, slot);
	EXPECT_EQ(k.colour->rgb.data(), pixels);
	EXPECT_EQ(k.colour->sequence, 7u);
	q.pop();
	EXPECT_EQ(q.freeSlot(), slot); // the keyed frame's slot is lent next
}
