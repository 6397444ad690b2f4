// The board calibration's fit: the pattern's circles as the colour camera
// sees them against where the board's computer drew them, a homography
// colour px -> board px fitted with OpenCV (cv::findHomography, RANSAC, so
// that a circle found wrongly cannot pull the fit), and its reprojection
// error in board pixels.
#pragma once

#include "algo/board_pattern.hpp"
#include "algo/homography.hpp"

#include <string>
#include <vector>

namespace depthkey {

struct BoardFit {
	Homography colourToBoard;
	int points = 0, inliers = 0;
	double rmsPx = 0, maxPx = 0;   // |H(colour centre) - board centre| over all circles, board px
};

// RANSAC's inlier threshold, board px: far above the error of a good
// detection, far below a circle mistaken for its neighbour.
constexpr double kBoardRansacPx = 3.0;

// -EINVAL with error set when fewer than 4 pairs or no homography fits.
int fitBoardHomography(const std::vector<ImagePoint> &colour, const std::vector<ImagePoint> &board,
		       BoardFit &fit, std::string &error);

// Finds the pattern in a colour picture of the board showing it and fits H.
// -ENOENT with error set when the whole grid is not in view.
int calibrateBoard(const RgbImage &colour, const BoardPattern &pattern, BoardFit &fit,
		   std::vector<ImagePoint> &found, std::string &error);

} // namespace depthkey
