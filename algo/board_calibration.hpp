// The board calibration's fit: the pattern's circles as the colour camera
// sees them against where the board's computer drew them, a homography
// colour px -> board px fitted with OpenCV (cv::findHomography, RANSAC, so
// that a circle found wrongly cannot pull the fit), and its reprojection
// error in board pixels.
//
// A webcam's barrel distortion bends the display's straight lines, which no
// homography follows. So the fit also finds the lens's two radial terms
// (algo/radial_lens.hpp): OpenCV's Nelder-Mead (cv::DownhillSolver) over
// (k1, k2), each step a least-squares homography (cv::findHomography) on the
// RANSAC inliers undistorted with them. The map is then
//   colour px --lens.undistort--> ideal px --colourToBoard--> board px.
#pragma once

#include "algo/board_pattern.hpp"
#include "algo/homography.hpp"
#include "algo/radial_lens.hpp"

#include <string>
#include <vector>

namespace depthkey {

struct BoardFit {
	Homography colourToBoard;      // ideal (undistorted) colour px -> board px
	RadialLens lens;               // the colour lens; a pinhole when fitLens was false
	int points = 0, inliers = 0;
	double rmsPx = 0, maxPx = 0;   // |H(colour centre) - board centre| over all circles, board px
};

// RANSAC's inlier threshold, board px: far above the error of a good
// detection, far below a circle mistaken for its neighbour.
constexpr double kBoardRansacPx = 3.0;

// Fewer circles than this and the lens terms are not fitted (a pinhole):
// two more unknowns need points well beyond the homography's four.
constexpr int kMinPointsForLens = 12;

// colourWidth x colourHeight: the image the circles were found in (the
// lens's centre and scale). -EINVAL with error set when fewer than 4 pairs
// or no homography fits.
int fitBoardHomography(const std::vector<ImagePoint> &colour, const std::vector<ImagePoint> &board,
		       int colourWidth, int colourHeight, bool fitLens, BoardFit &fit, std::string &error);

// Finds the pattern in a colour picture of the board showing it and fits H.
// -ENOENT with error set when the whole grid is not in view.
int calibrateBoard(const RgbImage &colour, const BoardPattern &pattern, BoardFit &fit,
		   std::vector<ImagePoint> &found, std::string &error, bool fitLens = true);

} // namespace depthkey
