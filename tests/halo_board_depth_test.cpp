// The halo's board depth (algo/halo_board_depth.hpp) against a double
// reference, and what it does: nothing without him nearby or without a
// halo, half-way to him at full cover and share 0.5, never nearer than him.
// Tolerance: each Q8 rounding (cover, f) is at most half a unit, so f is at
// most 1/256 off and the depth (zB - zS) / 256 + 1 mm.
#include "algo/halo_board_depth.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

using namespace depthkey;

namespace {

double haloBoardReference(int zB, double sum, double count, double area, int shareQ8)
{
	if (count == 0 || shareQ8 <= 0)
		return zB;
	const double zS = sum / count;
	if (zB <= zS)
		return zB;
	const double f = std::min(shareQ8, 230) / 256.0 * std::min(1.0, 2.0 * count / area);
	return zB - f * (zB - zS);
}

} // namespace

TEST(HaloBoardDepth, FixedPointMatchesTheDoubleReference)
{
	double worst = 0;
	int cases = 0;
	for (int area : { 9, 25, 81, 441 })
		for (int count = 0; count <= area; count += std::max(1, area / 17))
			for (int zS : { 400, 1200, 1999, 4000 })
				for (int zB : { 500, 2000, 2600, 7500 })
					for (int shareQ8 : { 0, 1, 64, 128, 200, 230, 255 }) {
						const uint32_t sum = uint32_t(zS) * uint32_t(count);
						const int fixed = haloBoardDepthMm(zB, sum, uint32_t(count), uint32_t(area), shareQ8);
						const double ref = haloBoardReference(zB, sum, count, area, shareQ8);
						const double tolerance = std::max(0, zB - zS) / 256.0 + 1.0;
						ASSERT_LE(std::abs(fixed - ref), tolerance)
							<< "zB " << zB << " zS " << zS << " count " << count << "/" << area
							<< " share " << shareQ8;
						worst = std::max(worst, std::abs(fixed - ref));
						++cases;
					}
	std::printf("halo board depth, fixed vs double: %d cases, worst %.2f mm\n", cases, worst);
}

TEST(HaloBoardDepth, ShiftsTheBoardTowardsHimByHowMuchOfHimIsAround)
{
	const uint32_t area = 81; // halo_px 4
	// Nobody around, or no halo: the board's own depth.
	EXPECT_EQ(haloBoardDepthMm(2000, 0, 0, area, 128), 2000);
	EXPECT_EQ(haloBoardDepthMm(2000, 1200 * 40, 40, area, 0), 2000);
	// He covers half the box or more (a straight silhouette, the gap
	// between arm and side): half-way at share 0.5.
	EXPECT_EQ(haloBoardDepthMm(2000, 1200 * 41, 41, area, 128), 1600);
	EXPECT_EQ(haloBoardDepthMm(2000, 1200 * 70, 70, area, 128), 1600);
	// A quarter of the box: half as much.
	const int quarter = haloBoardDepthMm(2000, 1200 * 20, 20, area, 128);
	EXPECT_NEAR(quarter, 1802, 2);
	// The more of him, the nearer; never nearer than he is, even at the
	// largest share.
	int last = 2000;
	for (uint32_t count = 1; count <= area; ++count) {
		const int z = haloBoardDepthMm(2000, 1200 * count, count, area, 230);
		EXPECT_LE(z, last);
		EXPECT_GE(z, 1200);
		last = z;
	}
	// A "board" nearer than him (furniture learned as background): kept.
	EXPECT_EQ(haloBoardDepthMm(1000, 1200 * 60, 60, area, 128), 1000);
}
