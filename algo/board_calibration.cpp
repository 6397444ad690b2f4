#include "algo/board_calibration.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>

#include <opencv2/calib3d.hpp>
#include <opencv2/core/optim.hpp>

namespace depthkey {

namespace {

// OpenCV's 3x3 result normalised to h[8] = 1; false when it is not one.
bool homographyFromMat(const cv::Mat &m, Homography &h)
{
	if (m.empty() || m.rows != 3 || m.cols != 3 || !(std::fabs(m.at<double>(2, 2)) > 1e-12))
		return false;
	for (int i = 0; i < 9; ++i)
		h.h[i] = m.at<double>(i / 3, i % 3) / m.at<double>(2, 2);
	return true;
}

// Least squares H on the points as seen through `lens` (undistorted);
// false when a point does not undistort or no H fits.
bool fitThroughLens(const std::vector<cv::Point2d> &seen, const std::vector<cv::Point2d> &board,
		    const RadialLens &lens, Homography &h)
{
	std::vector<cv::Point2d> ideal(seen.size());
	for (size_t i = 0; i < seen.size(); ++i)
		if (!lens.undistort(seen[i].x, seen[i].y, ideal[i].x, ideal[i].y))
			return false;
	cv::Mat m;
	try {
		m = cv::findHomography(ideal, board, 0);
	} catch (const cv::Exception &) {
		return false;
	}
	return homographyFromMat(m, h);
}

// Sum of squared board-px residuals of `h` after `lens`; +inf when a point
// does not map.
double squaredResiduals(const std::vector<cv::Point2d> &seen, const std::vector<cv::Point2d> &board,
			const RadialLens &lens, const Homography &h)
{
	double sum = 0;
	for (size_t i = 0; i < seen.size(); ++i) {
		double ix, iy, u, v;
		if (!lens.undistort(seen[i].x, seen[i].y, ix, iy) || !h.apply(ix, iy, u, v))
			return HUGE_VAL;
		sum += (u - board[i].x) * (u - board[i].x) + (v - board[i].y) * (v - board[i].y);
	}
	return sum;
}

// The objective Nelder-Mead sees: the residual of the best H for (k1, k2).
class LensObjective : public cv::MinProblemSolver::Function {
public:
	LensObjective(const std::vector<cv::Point2d> &seen, const std::vector<cv::Point2d> &board, int width, int height)
		: seen_(seen), board_(board), width_(width), height_(height)
	{
	}
	int getDims() const override { return 2; }
	double calc(const double *k) const override
	{
		const RadialLens lens = RadialLens::forImage(width_, height_, k[0], k[1]);
		Homography h;
		if (!fitThroughLens(seen_, board_, lens, h))
			return 1e30;
		const double sum = squaredResiduals(seen_, board_, lens, h);
		return std::isfinite(sum) ? sum : 1e30;
	}

private:
	const std::vector<cv::Point2d> &seen_, &board_;
	int width_, height_;
};

// (k1, k2) minimising the residual, and that residual (the squared sum of
// the least-squares H through the lens); false (a pinhole stays) when the
// solver fails or finds nothing better than no distortion.
bool fitLensTerms(const std::vector<cv::Point2d> &seen, const std::vector<cv::Point2d> &board, int width,
		  int height, RadialLens &lens, double &residual)
{
	cv::Ptr<LensObjective> objective = cv::makePtr<LensObjective>(seen, board, width, height);
	const double pinhole[2] = { 0, 0 };
	const double pinholeResidual = objective->calc(pinhole);
	try {
		// Steps of 0.05: a webcam's k1 is a few hundredths at a focal
		// length of one image width.
		const cv::Mat step = (cv::Mat_<double>(1, 2) << 0.05, 0.05);
		cv::Ptr<cv::DownhillSolver> solver = cv::DownhillSolver::create(
			objective, step,
			cv::TermCriteria(cv::TermCriteria::MAX_ITER + cv::TermCriteria::EPS, 2000, 1e-12));
		cv::Mat k = cv::Mat::zeros(1, 2, CV_64F);
		const double best = solver->minimize(k);
		if (!(best < pinholeResidual))
			return false;
		lens = RadialLens::forImage(width, height, k.at<double>(0), k.at<double>(1));
		residual = best;
		return true;
	} catch (const cv::Exception &) {
		return false;
	}
}

} // namespace

int fitBoardHomography(const std::vector<ImagePoint> &colour, const std::vector<ImagePoint> &board,
		       int colourWidth, int colourHeight, bool fitLens, BoardFit &fit, std::string &error)
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
	fit = BoardFit{};
	if (!homographyFromMat(h, fit.colourToBoard)) {
		error = "no homography fits the circles (are they in a straight grid?)";
		return -EINVAL;
	}
	fit.points = int(colour.size());
	fit.inliers = cv::countNonZero(mask);

	// The lens, on RANSAC's inliers: a circle found wrongly stays out.
	std::vector<cv::Point2d> seenIn, boardIn;
	for (size_t i = 0; i < src.size(); ++i)
		if (mask.at<uint8_t>(int(i)))
			seenIn.push_back(src[i]), boardIn.push_back(dst[i]);
	RadialLens lens;
	Homography throughLens;
	double lensResidual;
	if (fitLens && int(seenIn.size()) >= kMinPointsForLens && colourWidth > 1 && colourHeight > 1 &&
	    fitLensTerms(seenIn, boardIn, colourWidth, colourHeight, lens, lensResidual) &&
	    lensResidual < squaredResiduals(seenIn, boardIn, RadialLens{}, fit.colourToBoard) &&
	    fitThroughLens(seenIn, boardIn, lens, throughLens)) {
		fit.lens = lens;
		fit.colourToBoard = throughLens;
	}

	double sum = 0;
	for (size_t i = 0; i < colour.size(); ++i) {
		double ix, iy, u, v;
		if (!fit.lens.undistort(colour[i].x, colour[i].y, ix, iy) || !fit.colourToBoard.apply(ix, iy, u, v)) {
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
		   std::vector<ImagePoint> &found, std::string &error, bool fitLens)
{
	if (findColourGrid(colour, pattern.grid, found) < 0) {
		error = "the colour camera does not see the whole " + std::to_string(pattern.grid.cols) + "x" +
			std::to_string(pattern.grid.rows) +
			" circle grid on the board (is the pattern full screen, nobody in front of it, no glare?)";
		return -ENOENT;
	}
	return fitBoardHomography(found, pattern.centres(), colour.width(), colour.height(), fitLens, fit, error);
}

} // namespace depthkey
