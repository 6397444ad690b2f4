// The colour lens model of the board calibration (algo/radial_lens.hpp):
// undistort inverts distort over the whole image, a pinhole is the
// identity, and a lens that folds back is refused both ways.
#include "algo/radial_lens.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace depthkey;

TEST(RadialLens, UndistortInvertsDistortOverTheImage)
{
	const RadialLens lens = RadialLens::forImage(640, 480, -0.0341, 0.0064);
	double worst = 0, moved = 0;
	for (int y = 0; y < 480; y += 7)
		for (int x = 0; x < 640; x += 7) {
			double ix, iy, sx, sy;
			ASSERT_TRUE(lens.undistort(x, y, ix, iy)) << x << "," << y;
			ASSERT_TRUE(lens.distort(ix, iy, sx, sy));
			worst = std::max(worst, std::hypot(sx - x, sy - y));
			moved = std::max(moved, std::hypot(ix - x, iy - y));
		}
	EXPECT_LT(worst, 1e-6);
	// Barrel: the corners move outwards by a few pixels.
	EXPECT_GT(moved, 2.0);
	double ix, iy;
	lens.undistort(0, 0, ix, iy);
	EXPECT_LT(ix, 0);
	EXPECT_LT(iy, 0);
}

TEST(RadialLens, APinholeIsTheIdentity)
{
	const RadialLens lens = RadialLens::forImage(640, 480, 0, 0);
	EXPECT_TRUE(lens.isPinhole());
	double x, y;
	ASSERT_TRUE(lens.distort(12.25, 470.5, x, y));
	EXPECT_EQ(x, 12.25);
	EXPECT_EQ(y, 470.5);
	ASSERT_TRUE(lens.undistort(12.25, 470.5, x, y));
	EXPECT_EQ(x, 12.25);
	EXPECT_EQ(y, 470.5);
}

// k1 -0.9 with no k2: the seen radius r (1 - 0.9 r^2) peaks at r = 0.61 and
// falls after, so far-out points land inside the picture again.
TEST(RadialLens, ALensThatFoldsBackIsRefused)
{
	const RadialLens lens = RadialLens::forImage(640, 480, -0.9, 0);
	double ix, iy, x, y;
	EXPECT_FALSE(lens.undistort(0, 0, ix, iy)); // the corner's radius 0.625 is past the peak
	EXPECT_TRUE(lens.undistort(320, 240, ix, iy));
	EXPECT_TRUE(lens.distort(320 + 0.3 * 640, 240, x, y));
	EXPECT_FALSE(lens.distort(320 + 0.8 * 640, 240, x, y));
}
