// The board calibration pattern: a symmetric grid of black circles on white
// that the board's computer shows full screen (depthkey-calibrate
// --write-board-pattern), so that the colour camera sees the board's own
// pixels at known places. The grid covers the middle `fill` of the screen,
// so that a camera that sees the board with some wall to spare, or only its
// middle, still sees every circle; the homography is fitted on the circles
// and holds for the whole plane.
#pragma once

#include "algo/circle_grid_detector.hpp"
#include "algo/image.hpp"

namespace depthkey {

struct BoardPattern {
	int boardWidth = 1920, boardHeight = 1080; // the board picture's pixels
	GridSize grid{ 9, 5 };
	double fill = 0.55;                         // 0.2..0.95 of the screen the grid spans at most

	double spacingPx() const;                   // centre to centre, board px
	double radiusPx() const { return 0.25 * spacingPx(); } // diameter half the spacing
	// Circle i (row by row from the top left) centre, board px.
	ImagePoint centre(int i) const;
	std::vector<ImagePoint> centres() const;
	// How black the pattern is at board point (u, v), 0..1, over a footprint
	// of footprintPx board pixels (anti-aliased edges, as a display shows
	// them and the simulator renders them).
	double darkness(double u, double v, double footprintPx) const;
	// The picture for the board's screen, boardWidth x boardHeight.
	void render(RgbImage &out) const;
};

} // namespace depthkey
