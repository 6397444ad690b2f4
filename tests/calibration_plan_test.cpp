// The live calibration's plan (algo/calibration_plan.hpp): the views at each
// depth, and the default depths fitted to the room: the far surface read off
// a depth frame (the desk and monitor in front of it, and pixels that measured
// nothing, do not count), and the depths behind it or against it left out.
#include "algo/calibration_plan.hpp"

#include <gtest/gtest.h>

using namespace depthkey;

TEST(CalibrationPlan, FiveViewsAtEachDepth)
{
	const std::vector<PatternStep> plan = calibrationPlan({ 0.9, 1.6 });
	ASSERT_EQ(plan.size(), 10u);
	EXPECT_EQ(plan[0].where(), "middle");
	EXPECT_EQ(plan[1].where(), "top left");
	EXPECT_EQ(plan[9].where(), "bottom right");
	EXPECT_DOUBLE_EQ(plan[9].depthM, 1.6);
}

TEST(CalibrationPlan, TheFarSurfaceIsTheBoardNotTheDeskInFrontOfIt)
{
	// A ToF frame: the board at 2.04 m over most of it, a desk at 1.3 m
	// along the bottom third, a fifth of the pixels without a measurement.
	Gray16Image depth(160, 124, 2040);
	for (int y = 0; y < 124; ++y)
		for (int x = 0; x < 160; ++x) {
			if (y > 82)
				depth.row(y)[x] = 1300;
			if ((x + y) % 5 == 0)
				depth.row(y)[x] = 0;
		}
	EXPECT_EQ(farSurfaceMm(depth), 2040);
	// Mostly nothing measured (the camera covered): no surface.
	Gray16Image blind(160, 124, 0);
	blind.row(0)[0] = 900;
	EXPECT_EQ(farSurfaceMm(blind), 0);
}

TEST(CalibrationPlan, DepthsBehindOrAgainstTheBoardAreLeftOut)
{
	const std::vector<double> defaults = defaultCalibrationDepths();
	EXPECT_EQ(depthsInFrontOf(defaults, 2.04, 0.25), (std::vector<double>{ 0.9, 1.2, 1.6 }));
	EXPECT_EQ(depthsInFrontOf(defaults, 4.0, 0.25), defaults) << "a deep room keeps them all";
	EXPECT_TRUE(depthsInFrontOf(defaults, 1.0, 0.25).empty());
}
