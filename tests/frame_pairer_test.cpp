// Soft synchronisation: nearest depth within the skew, the offset, and the
// drop policy's counters.
#include <gtest/gtest.h>

#include "algo/frame_pairer.hpp"

using namespace depthkey;

namespace {

constexpr uint64_t kMs = 1'000'000;

DepthFrame depthAt(uint64_t ms)
{
	DepthFrame f;
	f.depthMm.resize(2, 1);
	f.depthMm.at(0, 0) = static_cast<uint16_t>(ms); // identifies the frame
	f.timestampNs = ms * kMs;
	return f;
}

int matchedMs(FramePairer &p, uint64_t colourMs)
{
	const DepthFrame *d = p.match(colourMs * kMs);
	return d ? d->depthMm.at(0, 0) : -1;
}

} // namespace

TEST(FramePairer, PairsTheNearestDepthWithinTheSkew)
{
	FramePairer p;
	p.configure(0, 60 * kMs);
	EXPECT_EQ(matchedMs(p, 1000), -1); // nothing yet
	p.addDepth(depthAt(1000));
	p.addDepth(depthAt(1100));
	EXPECT_EQ(matchedMs(p, 1040), 1000);
	EXPECT_EQ(matchedMs(p, 1060), 1100);
	EXPECT_EQ(matchedMs(p, 1160), 1100); // exactly max skew
	EXPECT_EQ(matchedMs(p, 1161), -1);   // too far: unkeyed
	EXPECT_EQ(matchedMs(p, 930), -1);
	EXPECT_EQ(p.stats().paired, 3u);
	EXPECT_EQ(p.stats().unpaired, 3u);
}

TEST(FramePairer, OffsetShiftsDepthTimestamps)
{
	FramePairer p;
	p.configure(-80 * kMs, 30 * kMs); // depth stamped 80 ms after exposure
	p.addDepth(depthAt(1080));
	p.addDepth(depthAt(1180));
	EXPECT_EQ(matchedMs(p, 1000), 1080);
	EXPECT_EQ(matchedMs(p, 1090), 1180);
	EXPECT_EQ(matchedMs(p, 1150), -1);
}

TEST(FramePairer, UnusedAndOutOfOrderDepthFramesAreCounted)
{
	FramePairer p;
	p.configure(0, 20 * kMs);
	constexpr uint64_t h = FramePairer::kHistory;
	for (uint64_t t = 0; t < h + 4; t++)
		p.addDepth(depthAt(1000 + 100 * t)); // 4 more frames than the history holds
	EXPECT_EQ(p.stats().depthUnused, 4u);
	const int newestMs = int(1000 + 100 * (h + 3));
	EXPECT_EQ(matchedMs(p, newestMs), newestMs);
	p.addDepth(depthAt(1500)); // older than the newest: refused
	EXPECT_EQ(p.stats().depthOutOfOrder, 1u);
	EXPECT_EQ(p.newest()->depthMm.at(0, 0), newestMs);
	for (uint64_t t = h + 4; t < 2 * h + 4; t++)
		p.addDepth(depthAt(1000 + 100 * t));
	EXPECT_EQ(p.stats().depthUnused, 4u + h - 1); // the newest was used
}

TEST(FramePairer, BracketsAColourFrameWithDepthFromBothSides)
{
	FramePairer p;
	p.configure(-40 * kMs, 150 * kMs); // depth stamped 40 ms after capture
	p.addDepth(depthAt(1040));          // captured 1000
	p.addDepth(depthAt(1140));          // captured 1100
	p.addDepth(depthAt(1240));          // captured 1200
	FramePairer::Bracket b = p.bracket(1130 * kMs);
	ASSERT_TRUE(b.before && b.after);
	EXPECT_EQ(b.before->depthMm.at(0, 0), 1140);
	EXPECT_EQ(b.after->depthMm.at(0, 0), 1240);
	EXPECT_EQ(b.beforeNs, int64_t(1100 * kMs));
	EXPECT_EQ(b.afterNs, int64_t(1200 * kMs));
	b = p.bracket(1200 * kMs); // at a depth capture: that one is before
	EXPECT_EQ(b.before->depthMm.at(0, 0), 1240);
	EXPECT_EQ(b.after, nullptr);
	b = p.bracket(900 * kMs);  // only later depth
	EXPECT_EQ(b.before, nullptr);
	EXPECT_EQ(b.after->depthMm.at(0, 0), 1040);
	b = p.bracket(1400 * kMs); // 200 ms after the newest: beyond the skew
	ASSERT_TRUE(b.stale()); // keyed with the newest all the same (issue 29)
	EXPECT_EQ(b.before->depthMm.at(0, 0), 1240);
	EXPECT_EQ(p.stats().paired, 3u);
	EXPECT_EQ(p.stats().unpaired, 0u);
}

// Issue 29 point 4: a colour frame with depth only beyond maxSkew is keyed
// with the nearest depth frame, flagged stale with the gap; depth more
// than a second away is lost: nothing (the board alone).
TEST(FramePairer, DepthBeyondTheSkewIsStaleAndBeyondASecondLost)
{
	FramePairer p;
	p.configure(0, 150 * kMs);
	p.addDepth(depthAt(1000));
	p.addDepth(depthAt(1100));
	FramePairer::Bracket b = p.bracket(1400 * kMs); // 300 ms after the newest
	ASSERT_TRUE(b.any());
	EXPECT_TRUE(b.stale());
	EXPECT_EQ(b.staleNs, int64_t(300 * kMs));
	ASSERT_NE(b.before, nullptr);
	EXPECT_EQ(b.before->depthMm.at(0, 0), 1100);
	EXPECT_EQ(b.after, nullptr);
	b = p.bracket(700 * kMs); // 300 ms before the oldest: after it
	ASSERT_NE(b.after, nullptr);
	EXPECT_EQ(b.after->depthMm.at(0, 0), 1000);
	EXPECT_EQ(b.staleNs, int64_t(300 * kMs));
	b = p.bracket(1100 * kMs + uint64_t(FramePairer::kLostNs)); // exactly a second
	EXPECT_TRUE(b.stale());
	b = p.bracket(1101 * kMs + uint64_t(FramePairer::kLostNs)); // over a second
	EXPECT_FALSE(b.any());
	EXPECT_FALSE(b.stale());
	b = p.bracket(1130 * kMs); // within the skew: not stale
	EXPECT_FALSE(b.stale());
	EXPECT_EQ(p.stats().stale, 3u);
	EXPECT_EQ(p.stats().unpaired, 1u);
	EXPECT_EQ(p.stats().paired, 1u);
}

TEST(FramePairer, ClearForgetsHistory)
{
	FramePairer p;
	p.configure(0, 100 * kMs);
	p.addDepth(depthAt(1000));
	p.clear();
	int64_t ns = 0;
	EXPECT_FALSE(p.newestNs(ns));
	EXPECT_EQ(p.newest(), nullptr);
	EXPECT_EQ(matchedMs(p, 1000), -1);
	p.addDepth(depthAt(500)); // after a restart, any time is accepted
	EXPECT_TRUE(p.newestNs(ns));
	EXPECT_EQ(ns, static_cast<int64_t>(500 * kMs));
}

TEST(FramePairer, DepthSlowerThanColourIsReused)
{
	FramePairer p;
	p.configure(0, 150 * kMs);
	int keyed = 0;
	// Depth at 10 fps, colour at 25 fps, both free running, depth 30 ms late.
	uint64_t nextDepth = 30;
	for (uint64_t c = 0; c < 1000; c += 40) {
		while (nextDepth <= c) {
			p.addDepth(depthAt(1000 + nextDepth));
			nextDepth += 100;
		}
		keyed += matchedMs(p, 1000 + c) >= 0;
	}
	EXPECT_EQ(keyed, 24); // all but the first colour frame (before any depth)
	EXPECT_EQ(p.stats().depthUnused, 0u);
}
