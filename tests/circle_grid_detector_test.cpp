// Finding the pattern in both cameras on the simulator's images, with the
// ToF noise of the paper, and failing clearly when it is not in view.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "algo/circle_grid_detector.hpp"
#include "hal/sim/calibration_pattern.hpp"
#include "tests/clutter_images.hpp"

#include <chrono>
#include <cstdio>

namespace depthkey {
namespace {

class CircleGridDetector : public ::testing::Test
{
protected:
	void SetUp() override
	{
		rig_.configure(640, 480, true, 60);
		renderer_.configure(rig_, board_, sim::PatternConditions{});
	}

	// True centres of the board's circles in the ToF image.
	std::vector<ImagePoint> tofTruth(const sim::PatternPose &pose) const
	{
		const double deg = 3.14159265358979323846 / 180.0;
		Eigen::Matrix3d r = (Eigen::AngleAxisd(pose.yawDeg * deg, Eigen::Vector3d::UnitY()) *
				     Eigen::AngleAxisd(pose.pitchDeg * deg, Eigen::Vector3d::UnitX()) *
				     Eigen::AngleAxisd(pose.rollDeg * deg, Eigen::Vector3d::UnitZ()))
					    .toRotationMatrix();
		std::vector<ImagePoint> out;
		for (int j = 0; j < board_.grid.count(); j++) {
			Eigen::Vector3d local((j % board_.grid.cols - (board_.grid.cols - 1) / 2.0) * board_.spacingM,
					      (j / board_.grid.cols - (board_.grid.rows - 1) / 2.0) * board_.spacingM, 0);
			ImagePoint p;
			rig_.tof().project(rig_.toTof(pose.centre + r * local), p.x, p.y);
			out.push_back(p);
		}
		return out;
	}

	CameraRig rig_;
	sim::PatternBoard board_;
	sim::PatternRenderer renderer_;
	ColourFrame colour_;
	DepthFrame depth_;
};

TEST_F(CircleGridDetector, FindsTheFarCornerPatternThroughToFNoise)
{
	// 2.5 m in a corner: the smallest circles (about 3.5 ToF pixels) where
	// vignetting leaves the least amplitude, so the most depth noise.
	sim::PatternPose pose = renderer_.poseFor({ 2.5, 1, 1 }, 3);
	renderer_.render(pose, 3, colour_, depth_);
	std::vector<ImagePoint> found;
	ASSERT_EQ(findAmplitudeGrid(depth_.amplitude, board_.grid, found), 0);
	std::vector<ImagePoint> truth = tofTruth(pose);
	double sum = 0;
	for (size_t i = 0; i < truth.size(); i++)
		sum += std::pow(found[i].x - truth[i].x, 2) + std::pow(found[i].y - truth[i].y, 2);
	// A tenth of a ToF pixel: about 0.4 colour pixels per point before the
	// fit averages hundreds of them.
	EXPECT_LT(std::sqrt(sum / truth.size()), 0.1);

	CalibrationView view;
	std::string error;
	ASSERT_EQ(pairView(colour_, depth_, board_.grid, view, error), 0) << error;
	EXPECT_EQ(view.points.size(), 35u);
	EXPECT_NEAR(view.depthM, 2.5, 0.08);
}

TEST_F(CircleGridDetector, PatternOutOfViewNamesBothCameras)
{
	sim::PatternPose pose;
	pose.centre = { 6.0, 0.0, 1.5 };        // far to the right of both
	renderer_.render(pose, 1, colour_, depth_);
	CalibrationView view;
	std::string error;
	EXPECT_EQ(pairView(colour_, depth_, board_.grid, view, error), -ENOENT);
	EXPECT_EQ(error.rfind("neither camera sees the whole 7x5 grid: colour: no circle found", 0), 0u) << error;
	// The ToF's noise makes a few dark spots, which the message does not
	// take for a grid cut by an edge.
	GridMiss tof = explainAmplitudeMiss(depth_.amplitude, board_.grid);
	EXPECT_NE(tof.kind, GridMiss::Kind::Cut) << tof.describe();
}

TEST_F(CircleGridDetector, PatternSeenOnlyByTheWiderToFNamesTheColourCamera)
{
	// The ToF's lens is wider: at the left edge the colour image cuts the
	// board while the ToF still sees all of it.
	sim::PatternPose pose;
	pose.centre = { -1.1, 0.0, 2.5 };
	renderer_.render(pose, 1, colour_, depth_);
	CalibrationView view;
	std::string error;
	EXPECT_EQ(pairView(colour_, depth_, board_.grid, view, error), -ENOENT);
	// It says how much it saw and where the grid leaves the picture.
	EXPECT_EQ(error.rfind("the colour camera does not see the whole 7x5 grid: ", 0), 0u) << error;
	GridMiss miss = explainColourMiss(colour_.rgb, board_.grid);
	EXPECT_EQ(miss.kind, GridMiss::Kind::Cut) << miss.describe();
	EXPECT_EQ(miss.edges, "left");
	EXPECT_GT(miss.circles, 0);
	EXPECT_LT(miss.circles, 35);
	EXPECT_NE(error.find(std::to_string(miss.circles) + " of 35 circles found, whole columns are missing at the image's left edge"),
		  std::string::npos)
		<< error;
}

TEST_F(CircleGridDetector, PatternHiddenFromTheToFNamesIt)
{
	renderer_.render(renderer_.poseFor({ 1.6, 0, 0 }, 0), 1, colour_, depth_);
	std::fill_n(depth_.amplitude.data(), depth_.amplitude.size(), uint16_t{ 800 });
	CalibrationView view;
	std::string error;
	EXPECT_EQ(pairView(colour_, depth_, board_.grid, view, error), -ENOENT);
	EXPECT_EQ(error, "the ToF camera does not see the whole 7x5 grid in its amplitude image: no circle found: "
			 "the pattern is out of view, too far, or too dark");
}

TEST_F(CircleGridDetector, PatternPartlyCoveredInTheMiddleIsCalledHidden)
{
	// The lower middle of the pattern behind something the paper's colour
	// (a monitor's back, the desk): whole circles gone, none cut by an edge.
	renderer_.render(renderer_.poseFor({ 1.6, 0, 0 }, 0), 1, colour_, depth_);
	std::vector<ImagePoint> centres;
	ASSERT_EQ(findColourGrid(colour_.rgb, board_.grid, centres), 0);
	double half = (centres[9].x - centres[8].x) / 2;
	double x0 = centres[8].x - half, x1 = centres[12].x + half, y0 = (centres[15].y + centres[22].y) / 2;
	for (int y = static_cast<int>(y0); y < colour_.rgb.height(); y++)
		for (int x = static_cast<int>(x0); x <= static_cast<int>(x1); x++)
			colour_.rgb.at(x, y) = Rgb8{ 200, 200, 200 };
	CalibrationView view;
	std::string error;
	EXPECT_EQ(pairView(colour_, depth_, board_.grid, view, error), -ENOENT);
	GridMiss miss = explainColourMiss(colour_.rgb, board_.grid);
	EXPECT_EQ(miss.kind, GridMiss::Kind::Hidden) << miss.describe();
	EXPECT_EQ(miss.circles, 35 - 2 * 5); // rows 4 and 5, columns 2 to 6 (from 1)
	EXPECT_NE(error.find("25 of 35 circles found, not whole columns or rows at the image's edge: the rest are hidden"), std::string::npos)
		<< error;
}

TEST_F(CircleGridDetector, AWholeGridSaysSo)
{
	renderer_.render(renderer_.poseFor({ 1.6, 0, 0 }, 0), 1, colour_, depth_);
	EXPECT_EQ(explainColourMiss(colour_.rgb, board_.grid).kind, GridMiss::Kind::NotAGrid); // all 35, as blobs
	EXPECT_EQ(explainColourMiss(colour_.rgb, board_.grid).circles, 35);
}

TEST(DepthAround, TakesThePaperNotTheNoisyCircle)
{
	DepthFrame d;
	d.depthMm = Gray16Image(20, 20, 1500);
	d.amplitude = Gray16Image(20, 20, 4000);
	// A dark circle of wild depths in the middle, one invalid pixel.
	for (int y = 7; y <= 13; y++)
		for (int x = 7; x <= 13; x++) {
			d.amplitude.at(x, y) = 200;
			d.depthMm.at(x, y) = static_cast<uint16_t>(900 + 97 * ((x * 7 + y * 13) % 11));
		}
	d.depthMm.at(3, 10) = 0;
	EXPECT_DOUBLE_EQ(depthAround(d, { 10, 10 }, 8.0), 1.5);
	d.depthMm = Gray16Image(20, 20, 0);
	EXPECT_EQ(depthAround(d, { 10, 10 }, 8.0), 0.0);
}

// Issue 31 point 12: frames full of blobs and no pattern made the grid
// search run for minutes (cubic in the blob count). They are refused as
// clutter, naming it; the time each took is printed (the bound is measured
// in tests/bench/circle_grid_bench.cpp, not asserted here).
int timedFind(const char *what, const RgbImage &rgb, GridSize grid)
{
	std::vector<ImagePoint> found;
	auto start = std::chrono::steady_clock::now();
	int ret = findColourGrid(rgb, grid, found);
	std::printf("%s: %d in %.3f s\n", what, ret,
		    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
	return ret;
}

TEST(CircleGridClutter, AFieldOfDotsIsRefusedAsClutter)
{
	EXPECT_EQ(timedFind("640x480, 2100 dots", test::dotField(640, 480, 2100), GridSize{}), -E2BIG);
	EXPECT_EQ(timedFind("640x480, 520 dots", test::dotField(640, 480, 520), GridSize{}), -E2BIG);
	EXPECT_EQ(timedFind("640x480 noise", test::noiseImage(640, 480), GridSize{}), -E2BIG);
}

TEST(CircleGridClutter, LargeNoiseAndDotFramesAreRefusedAsClutter)
{
	EXPECT_EQ(timedFind("1920x1080 noise", test::noiseImage(1920, 1080), GridSize{}), -E2BIG);
	EXPECT_EQ(timedFind("1920x1080, 4800 dots", test::dotField(1920, 1080, 4800), GridSize{}), -E2BIG);
}

// The reason a live view gives (issue 30) is asked on depthkey-calibrate
// --live's loop every half second: bounded as the search is, it calls such a
// frame too many, not after seconds of blob detection at full size.
TEST(CircleGridClutter, TheMissReasonOfNoiseAndDotsIsTooMany)
{
	for (const auto &[what, rgb] : { std::pair{ "1920x1080 noise", test::noiseImage(1920, 1080) },
					 { "640x480, 2100 dots", test::dotField(640, 480, 2100) } }) {
		auto start = std::chrono::steady_clock::now();
		const GridMiss miss = explainColourMiss(rgb, GridSize{});
		std::printf("%s: explained in %.3f s: %s\n", what,
			    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
			    miss.describe().c_str());
		EXPECT_EQ(miss.kind, GridMiss::Kind::TooMany) << what;
		EXPECT_GT(miss.circles, GridSize{}.count()) << what;
		EXPECT_NE(miss.describe().find("circle-like blobs for the 35 circles"), std::string::npos) << what;
	}
}

TEST_F(CircleGridDetector, ClutterIsNamedWithItsCamera)
{
	renderer_.render(renderer_.poseFor({ 1.6, 0, 0 }, 0), 1, colour_, depth_);
	colour_.rgb = test::dotField(640, 480, 2100);
	CalibrationView view;
	std::string error;
	EXPECT_EQ(pairView(colour_, depth_, board_.grid, view, error), -E2BIG);
	EXPECT_EQ(error, "the colour camera sees more than 140 circle-like blobs (4 for each circle of the 7x5 "
			 "grid): clutter or noise, not searched for the pattern");
}

TEST(CircleGrid1080p, APatternInAFullHdFrameIsFoundAtFullSizeAccuracy)
{
	// Searched at half size, refined at full size: the centres agree with
	// the same view at 640x480 scaled by 3.
	CameraRig small, large;
	small.configure(640, 480, false, 60);
	large.configure(1920, 1440, false, 60);
	sim::PatternBoard board;
	sim::PatternRenderer smallRenderer, largeRenderer;
	smallRenderer.configure(small, board, sim::PatternConditions{});
	largeRenderer.configure(large, board, sim::PatternConditions{});
	sim::PatternPose pose = smallRenderer.poseFor({ 1.6, 0, 0 }, 0);
	ColourFrame smallColour, largeColour;
	DepthFrame depth;
	smallRenderer.render(pose, 1, smallColour, depth);
	largeRenderer.render(pose, 1, largeColour, depth);
	std::vector<ImagePoint> inSmall, inLarge;
	ASSERT_EQ(findColourGrid(smallColour.rgb, board.grid, inSmall), 0);
	ASSERT_EQ(timedFind("1920x1440 pattern", largeColour.rgb, board.grid), 0);
	ASSERT_EQ(findColourGrid(largeColour.rgb, board.grid, inLarge), 0);
	ASSERT_EQ(inSmall.size(), inLarge.size());
	double worst = 0;
	for (size_t i = 0; i < inSmall.size(); i++)
		worst = std::max(worst, std::hypot((inLarge[i].x + 0.5) / 3 - 0.5 - inSmall[i].x,
						   (inLarge[i].y + 0.5) / 3 - 0.5 - inSmall[i].y));
	EXPECT_LT(worst, 0.15); // 640x480 pixels
}

} // namespace
} // namespace depthkey
