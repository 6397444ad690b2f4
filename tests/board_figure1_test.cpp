// make run's composite is the paper's Figure 1: the board's strokes stay
// visible through the lecturer. Checked on the simulator's truth: make run's
// board (board.backend "sim", 1920 px wide), its board calibration (the one
// depthkey-calibrate --board --sim fits, lens distortion on), the shipped
// opacity, and the lecturer's true alpha as the key, at moments when he
// stands writing in front of what he wrote.
#include "algo/board_calibration.hpp"
#include "algo/board_compositor.hpp"
#include "algo/composite.hpp"
#include "hal/sim/board_display.hpp"
#include "hal/sim/lecture_simulator.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>

using namespace depthkey;

TEST(BoardFigure1, StrokesShowThroughTheLecturerInMakeRunsComposite)
{
	const Settings shipped;
	const int bw = shipped.board.width, bh = simBoardHeight(bw);

	// The board calibration make run fits.
	LectureSimulator shot;
	SimSettings calib = shipped.sim;
	calib.table = false;
	shot.configure(calib, shipped.colour.width, shipped.colour.height);
	shot.setLecturerVisible(false);
	BoardPattern pattern{ bw, bh };
	RgbImage picture;
	pattern.render(picture);
	shot.showOnBoard(picture);
	ColourFrame colour;
	shot.renderColour(1.0, colour);
	BoardFit fit;
	std::vector<ImagePoint> found;
	std::string error;
	ASSERT_EQ(calibrateBoard(colour.rgb, pattern, fit, found, error), 0) << error;

	LectureSimulator lecture;
	lecture.configure(shipped.sim, shipped.colour.width, shipped.colour.height);
	SimBoardDisplay display;
	display.configure(shipped.sim, bw);
	BoardCompositor compositor;
	ASSERT_TRUE(compositor.configure(fit.colourToBoard, shipped.colour.width, shipped.colour.height, bw, bh));
	const int opacityQ8 = opacityToQ8(shipped.composite.opacity);

	// The end of the first writing phase: his arm and body in front of two
	// fresh lines.
	const sim::LectureScript &script = lecture.script();
	double writeEnd = 0;
	for (double t = 0; t < script.cycleLength(); t += 0.1)
		if (script.phaseAt(t).action == sim::LecturerAction::Write) {
			writeEnd = script.phaseAt(t).end;
			break;
		}
	ASSERT_GT(writeEnd, 0);

	size_t under = 0;
	double throughSum = 0, inkSum = 0;
	RgbImage board, blank, composite, blankComposite;
	RgbaImage layer, blankLayer, cameraLayer;
	for (double t : { writeEnd - 0.9, writeEnd - 0.5, writeEnd - 0.1 }) {
		GroundTruth truth;
		lecture.renderColour(t, colour, &truth);
		display.render(t, board);
		display.render(std::floor(t / script.cycleLength()) * script.cycleLength() + 0.01, blank); // no ink yet
		Roi roi{ colour.rgb.width(), colour.rgb.height(), 0, 0 };
		for (int y = 0; y < colour.rgb.height(); ++y)
			for (int x = 0; x < colour.rgb.width(); ++x)
				if (truth.alpha.at(x, y)) {
					roi = { std::min(roi.x0, x), std::min(roi.y0, y), std::max(roi.x1, x + 1), std::max(roi.y1, y + 1) };
				}
		lecturerLayer(colour.rgb, truth.alpha, cameraLayer);
		compositor.compose(cameraLayer, roi, board, opacityQ8, composite, layer);
		compositor.compose(cameraLayer, roi, blank, opacityQ8, blankComposite, blankLayer);
		for (int y = 0; y < bh; ++y)
			for (int x = 0; x < bw; ++x) {
				const Rgb8 ink = board.at(x, y), paper = blank.at(x, y);
				int inkContrast = std::abs(ink.r - paper.r) + std::abs(ink.g - paper.g) + std::abs(ink.b - paper.b);
				if (inkContrast < 150 || layer.at(x, y).a < 230)
					continue; // not a stroke, or not behind the lecturer
				const Rgb8 a = composite.at(x, y), b = blankComposite.at(x, y);
				throughSum += std::abs(a.r - b.r) + std::abs(a.g - b.g) + std::abs(a.b - b.b);
				inkSum += inkContrast;
				under++;
			}
	}
	// He stands in front of his writing (hundreds of stroke pixels)...
	ASSERT_GT(under, 300u);
	// ...and it shows through him at the opacity's share of its contrast
	// (0.5 here; at least 80% of that, the rest is alpha below 1 at edges).
	double share = throughSum / inkSum;
	std::printf("figure 1: %zu stroke pixels behind the lecturer, shown at %.2f of their contrast\n", under, share);
	EXPECT_GT(share, 0.8 * (1.0 - shipped.composite.opacity)) << under << " stroke pixels behind him";
	EXPECT_LT(share, 1.0);
}
