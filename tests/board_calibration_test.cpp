// The board calibration: the homography found from the simulator's board
// showing the pattern against the simulator's truth, RANSAC against a
// circle found in the wrong place, and depthkey-calibrate --board end to end
// (pattern file, summary line, the written file, the refusal limit).
#include "algo/board_calibration.hpp"
#include "config/board_calibration_file.hpp"
#include "hal/image_file.hpp"
#include "hal/sim/board_display.hpp"
#include "hal/sim/lecture_simulator.hpp"
#include "tests/process/shell_command.hpp"
#include "tests/test_paths.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

using namespace depthkey;

namespace {

struct Shot {
	LectureSimulator simulator;
	ColourFrame colour;
	BoardPattern pattern{ 1920, simBoardHeight(1920) };
};

void shoot(Shot &shot, bool distortion)
{
	SimSettings s;
	s.distortion = distortion;
	s.table = false;
	shot.simulator.configure(s, 640, 480);
	shot.simulator.setLecturerVisible(false);
	RgbImage picture;
	shot.pattern.render(picture);
	shot.simulator.showOnBoard(picture);
	shot.simulator.renderColour(1.0, shot.colour);
}

// RMS over the display the camera sees of |H(x) - truth(x)|, board px.
double rmsAgainstTruth(const Shot &shot, const BoardFit &fit, double &worst)
{
	double sum = 0;
	int n = 0;
	worst = 0;
	const int bw = shot.pattern.boardWidth, bh = shot.pattern.boardHeight;
	for (int y = 0; y < 480; y += 4)
		for (int x = 0; x < 640; x += 4) {
			double tu, tv, ix, iy, u, v;
			if (!simColourToBoard(shot.simulator.rig(), 2.0, bw, bh, x, y, tu, tv) || tu < -0.5 ||
			    tv < -0.5 || tu > bw - 0.5 || tv > bh - 0.5 || !fit.lens.undistort(x, y, ix, iy) ||
			    !fit.colourToBoard.apply(ix, iy, u, v))
				continue;
			double e = std::hypot(u - tu, v - tv);
			sum += e * e;
			worst = std::max(worst, e);
			n++;
		}
	EXPECT_GT(n, 10000);
	return std::sqrt(sum / n);
}

} // namespace

// The bar: the true H within 0.5 board px RMS over the display. It
// exists when the colour lens is a pinhole.
TEST(BoardCalibration, RecoversTheSimulatorsTrueHomography)
{
	Shot shot;
	shoot(shot, false);
	BoardFit fit;
	std::vector<ImagePoint> found;
	std::string error;
	ASSERT_EQ(calibrateBoard(shot.colour.rgb, shot.pattern, fit, found, error), 0) << error;
	EXPECT_EQ(fit.inliers, 45);
	EXPECT_LT(fit.rmsPx, 0.1);
	double worst;
	EXPECT_LT(rmsAgainstTruth(shot, fit, worst), 0.5);
	// A pinhole seen as one: whatever lens terms the fit keeps are too
	// small to move a corner pixel by a tenth of a pixel.
	double cx, cy;
	fit.lens.distort(0, 0, cx, cy);
	EXPECT_LT(std::hypot(cx, cy), 0.1) << "k1 " << fit.lens.k1 << " k2 " << fit.lens.k2;
	// And the coefficients: the true H is a scale and shift (the sim camera
	// faces the board), maps the image's corners where it does.
	Homography truth = simTrueHomography(shot.simulator.rig(), 2.0, 1920, simBoardHeight(1920));
	for (auto [x, y] : { std::pair{ 0.0, 0.0 }, { 639.0, 0.0 }, { 0.0, 479.0 }, { 639.0, 479.0 } }) {
		double u, v, tu, tv;
		fit.colourToBoard.apply(x, y, u, v);
		truth.apply(x, y, tu, tv);
		EXPECT_NEAR(u, tu, 0.5);
		EXPECT_NEAR(v, tv, 0.5);
	}
}

// With the webcam's barrel distortion no homography is exact (1.55 board px
// RMS as a pinhole): the fit finds the lens's radial terms too, and the
// issue's bar holds, the truth within 0.5 board px RMS over the display.
TEST(BoardCalibration, WithLensDistortionTheFittedLensRecoversTheTruth)
{
	Shot shot;
	shoot(shot, true);
	std::vector<ImagePoint> found;
	std::string error;
	BoardFit pinhole;
	ASSERT_EQ(calibrateBoard(shot.colour.rgb, shot.pattern, pinhole, found, error, false), 0) << error;
	EXPECT_TRUE(pinhole.lens.isPinhole());
	double worst;
	const double pinholeRms = rmsAgainstTruth(shot, pinhole, worst);
	EXPECT_GT(pinholeRms, 1.0) << "the simulator's lens should defeat a homography alone";

	BoardFit fit;
	ASSERT_EQ(calibrateBoard(shot.colour.rgb, shot.pattern, fit, found, error), 0) << error;
	EXPECT_EQ(fit.inliers, 45);
	EXPECT_LT(fit.rmsPx, 0.3);
	const double rms = rmsAgainstTruth(shot, fit, worst);
	std::printf("board fit against the simulator's truth: pinhole %.3f, with the lens %.3f board px RMS (max %.3f), "
		    "k1 %.5f k2 %.5f\n", pinholeRms, rms, worst, fit.lens.k1, fit.lens.k2);
	EXPECT_LT(rms, 0.5);
	// The simulator's lens (k1 -0.03, k2 0.005 at its focal length of 600
	// px) at a focal length of one image width, 640 px: k1 -0.0341.
	const double scale2 = (640.0 / 600.0) * (640.0 / 600.0);
	EXPECT_NEAR(fit.lens.k1, -0.03 * scale2, 0.01);
}

TEST(BoardCalibration, RansacIgnoresACircleFoundInTheWrongPlace)
{
	BoardPattern pattern{ 1920, 1080 };
	std::vector<ImagePoint> board = pattern.centres(), colour;
	Homography inverse;
	Homography h;
	h.h = { 0.3, 0.02, 40, -0.01, 0.31, 25, 1e-5, 2e-5, 1 };
	h.inverse(inverse);
	for (const ImagePoint &p : board) {
		double x = 0, y = 0;
		inverse.apply(p.x, p.y, x, y);
		colour.push_back({ x, y });
	}
	colour[7].x += 25; // one blob mistaken
	BoardFit fit;
	std::string error;
	ASSERT_EQ(fitBoardHomography(colour, board, 640, 480, true, fit, error), 0) << error;
	EXPECT_EQ(fit.inliers, pattern.grid.count() - 1);
	double ix, iy, u, v;
	ASSERT_TRUE(fit.lens.undistort(300, 200, ix, iy));
	fit.colourToBoard.apply(ix, iy, u, v);
	double tu, tv;
	h.apply(300, 200, tu, tv);
	EXPECT_NEAR(u, tu, 0.01);
	EXPECT_NEAR(v, tv, 0.01);
	// The error report still shows the bad circle.
	EXPECT_GT(fit.maxPx, 5.0);
}

TEST(BoardCalibration, RefusesAPictureWithoutTheWholeGrid)
{
	BoardPattern pattern;
	RgbImage grey(640, 480, Rgb8{ 128, 128, 128 });
	BoardFit fit;
	std::vector<ImagePoint> found;
	std::string error;
	EXPECT_EQ(calibrateBoard(grey, pattern, fit, found, error), -ENOENT);
	EXPECT_NE(error.find("does not see the whole 9x5 circle grid"), std::string::npos) << error;
}
