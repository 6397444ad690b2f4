// The trimap of a colour frame keyed with depth from both sides in time
// (algo/trimap_union.hpp): the labels' union and intersection, the depth
// evidence blended by time, and an edge that moved between the two depth
// captures followed to where it is at the colour frame's time.
#include <gtest/gtest.h>

#include "algo/trimap.hpp"
#include "algo/trimap_union.hpp"

#include <cstring>
#include <random>
#include <vector>

using namespace depthkey;

namespace {

constexpr uint8_t kSureLecturer = 254, kSureBoard = 1;

// One row of evidence: lecturer (sure) on [0, edge), board (sure) after.
std::vector<uint8_t> stepRow(int width, int edge)
{
	std::vector<uint8_t> row(size_t(width), kSureBoard);
	std::memset(row.data(), kSureLecturer, size_t(edge));
	return row;
}

// Where the lecturer-like evidence of a row ends.
int edgeOf(const std::vector<uint8_t> &row)
{
	int x = 0;
	while (x < int(row.size()) && row[size_t(x)] > 128)
		++x;
	return x;
}

std::vector<uint8_t> blendRows(const std::vector<uint8_t> &a, const std::vector<uint8_t> &b, int laterQ8)
{
	std::vector<uint8_t> out(a.size());
	for (size_t i = 0; i < a.size(); ++i)
		out[i] = uint8_t((a[i] * (256 - laterQ8) + b[i] * laterQ8 + 128) >> 8);
	return out;
}

MappedSeeds seedsWith(int width, int height, Roi roi, uint8_t label, uint8_t evidence)
{
	MappedSeeds s;
	s.trimap.resize(width, height);
	s.evidence.resize(width, height);
	std::memset(s.trimap.data(), kTrimapBoard, s.trimap.size());
	std::memset(s.evidence.data(), 0, s.evidence.size());
	for (int y = roi.y0; y < roi.y1; ++y)
		for (int x = roi.x0; x < roi.x1; ++x) {
			s.trimap.at(x, y) = label;
			s.evidence.at(x, y) = evidence;
		}
	s.roi = roi;
	return s;
}

} // namespace

TEST(TrimapUnion, AnEdgeThatMovedIsWhereItIsAtTheColourFramesTime)
{
	// He walks right: his edge is at 10 in the earlier depth frame and at
	// 30 in the later one.
	const auto a = stepRow(64, 10), b = stepRow(64, 30);
	for (int laterQ8 : { 0, 64, 128, 192, 256 }) {
		auto out = blendRows(a, b, laterQ8);
		interpolateEdgesInRow(a.data(), b.data(), 0, 64, laterQ8, out.data());
		EXPECT_EQ(edgeOf(out), 10 + (20 * laterQ8 + 128) / 256) << "laterQ8 " << laterQ8;
		// Only the swept run changed; beyond it both frames agree.
		EXPECT_EQ(out[5], kSureLecturer);
		EXPECT_EQ(out[40], kSureBoard);
	}
	// Walking left, the mirror image.
	const auto c = stepRow(64, 30), d = stepRow(64, 10);
	auto out = blendRows(c, d, 64);
	interpolateEdgesInRow(c.data(), d.data(), 0, 64, 64, out.data());
	EXPECT_EQ(edgeOf(out), 25);
}

TEST(TrimapUnion, WithoutAnEdgeToFollowOrSureDepthTheBlendStays)
{
	// All of an arm moved away (no lecturer beside the run in both frames).
	std::vector<uint8_t> a(32, kSureBoard), b(32, kSureBoard);
	std::memset(a.data() + 4, kSureLecturer, 6);
	std::memset(b.data() + 20, kSureLecturer, 6);
	auto out = blendRows(a, b, 128), blended = out;
	interpolateEdgesInRow(a.data(), b.data(), 0, 32, 128, out.data());
	EXPECT_EQ(out, blended);
	// Noisy depth that leans either way without being sure: not followed.
	std::vector<uint8_t> c(32, 150), d(32, 110);
	std::memset(c.data(), kSureLecturer, 4);
	std::memset(d.data(), kSureLecturer, 4);
	out = blendRows(c, d, 128);
	blended = out;
	interpolateEdgesInRow(c.data(), d.data(), 0, 32, 128, out.data());
	EXPECT_EQ(out, blended);
}

TEST(TrimapUnion, TheCoreIsWhereBothSawHimTheSupersetWhereEither)
{
	const MappedSeeds a = seedsWith(40, 20, { 5, 5, 20, 15 }, kTrimapLecturer, kSureLecturer);
	const MappedSeeds b = seedsWith(40, 20, { 10, 5, 25, 15 }, kTrimapLecturer, kSureLecturer);
	MappedSeeds out;
	uniteTrimaps(a, b, 128, out);
	EXPECT_EQ(out.roi, (Roi{ 5, 5, 25, 15 }));
	EXPECT_EQ(out.trimap.at(15, 10), kTrimapLecturer);           // both
	EXPECT_NE(out.trimap.at(7, 10), kTrimapLecturer);            // a only
	EXPECT_NE(out.trimap.at(7, 10), kTrimapBoard);
	EXPECT_NE(out.trimap.at(22, 10), kTrimapBoard);              // b only
	EXPECT_EQ(out.trimap.at(30, 10), kTrimapBoard);              // neither
	EXPECT_EQ(out.evidence.at(15, 10), kSureLecturer);
	// A colour frame right at a's capture: where only a saw him, a's say.
	uniteTrimaps(a, b, 0, out);
	EXPECT_GT(out.evidence.at(7, 10), 128);
	EXPECT_LT(out.evidence.at(22, 10), 128);
}

// One depth frame united with itself (the pipeline with no later depth
// frame) is copied, not blended: the copy must equal the blend of two equal
// frames bit for bit, whatever the time, and clear what an earlier, larger
// union painted.
TEST(TrimapUnion, AFrameUnitedWithItselfEqualsTheBlendOfTwoEqualFrames)
{
	std::mt19937 random(28);
	std::uniform_int_distribution<int> value(0, 255);
	MappedSeeds a = seedsWith(64, 48, { 3, 4, 60, 40 }, kTrimapUndecided, 128);
	for (int y = 4; y < 40; ++y)
		for (int x = 3; x < 60; ++x) {
			a.trimap.at(x, y) = uint8_t(value(random));
			a.evidence.at(x, y) = uint8_t(value(random));
		}
	const MappedSeeds copy = a;
	const MappedSeeds wide = seedsWith(64, 48, { 0, 0, 64, 48 }, kTrimapInRange, 200);
	for (int laterQ8 : { 0, 1, 77, 128, 255, 256 }) {
		MappedSeeds fast, blended;
		uniteTrimaps(wide, wide, 0, fast); // an earlier union over all of the image
		uniteTrimaps(a, a, laterQ8, fast);
		uniteTrimaps(a, copy, laterQ8, blended);
		EXPECT_EQ(fast.roi, blended.roi);
		EXPECT_EQ(0, std::memcmp(fast.trimap.data(), blended.trimap.data(), fast.trimap.size())) << laterQ8;
		EXPECT_EQ(0, std::memcmp(fast.evidence.data(), blended.evidence.data(), fast.evidence.size())) << laterQ8;
	}
}
