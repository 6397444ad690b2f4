#include "algo/board_calibration.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>

#include <opencv2/calib3d.hpp>

namespace depthkey {

int fitBoardHomography(const std::vector<ImagePoint> &colour, const std::vector<ImagePoint> &board,
		       BoardFit &fit, std::string &error)
{
	if (colour.size() != board.size() || colour.size() < 4) {
		error = "a homography needs at least 4 circle pairs, got " + std::to_string(colour.size());
		return -EINVAL;
	}
	std::vector<cv::Point2d> src, dst;
	for (size_t i = 0; i < colour.size(); ++i) {
		src.emplace_back(colour[i].x, colour[i].y);
		dst.emplace_back(board[i].x, board[i].y);
	}
	cv::Mat mask;
	cv::Mat h;
	try {
		h = cv::findHomography(src, dst, cv::RANSAC, kBoardRansacPx, mask);
	} catch (const cv::Exception &e) {
		h.release();
	}
	if (h.empty() || h.rows != 3 || h.cols != 3) {
		error = "no homography fits the circles (are they in a straight grid?)";
		return -EINVAL;
	}
	fit = BoardFit{};
	for (int i = 0; i < 9; ++i)
		fit.colourToBoard.h[i] = h.at<double>(i / 3, i % 3) / h.at<double>(2, 2);
	fit.points = int(colour.size());
	fit.inliers = cv::countNonZero(mask);
	double sum = 0;
	for (size_t i = 0; i < colour.size(); ++i) {
		double u, v;
		if (!fit.colourToBoard.apply(colour[i].x, colour[i].y, u, v)) {
			error = "the homography maps a circle to infinity";
			return -EINVAL;
		}
		double e = std::hypot(u - board[i].x, v - board[i].y);
		sum += e * e;
		fit.maxPx = std::max(fit.maxPx, e);
	}
	fit.rmsPx = std::sqrt(sum / colour.size());
	return 0;
}

int calibrateBoard(const RgbImage &colour, const BoardPattern &pattern, BoardFit &fit,
		   std::vector<ImagePoint> &found, std::string &error)
{
	if (findColourGrid(colour, pattern.grid, found) < 0) {
		error = "the colour camera does not see the whole " + std::to_string(pattern.grid.cols) + "x" +
			std::to_string(pattern.grid.rows) +
			" circle grid on the board (is the pattern full screen, nobody in front of it, no glare?)";
		return -ENOENT;
	}
	return fitBoardHomography(found, pattern.centres(), fit, error);
}

} // namespace depthkey
