// Circle-grid detection in both cameras with OpenCV, and the pairing.
#include "algo/circle_grid_detector.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>

#include <opencv2/calib3d.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

namespace depthkey {

namespace {

// Blob limits for an image of the given size: a circle covers at least a
// few pixels and at most the whole grid's share of the image. Circularity and
// convexity are loosened so a pattern tilted by 45 degrees (ellipses) and a
// noisy ToF edge still pass.
cv::Ptr<cv::FeatureDetector> blobDetector(int width, int height, GridSize grid, double minArea)
{
	cv::SimpleBlobDetector::Params p;
	p.minThreshold = 20;
	p.maxThreshold = 230;
	p.thresholdStep = 10;
	p.filterByColor = true;
	p.blobColor = 0;
	p.filterByArea = true;
	p.minArea = static_cast<float>(minArea);
	p.maxArea = static_cast<float>(static_cast<double>(width) * height / grid.count());
	p.filterByCircularity = true;
	p.minCircularity = 0.5f;
	p.filterByConvexity = true;
	p.minConvexity = 0.8f;
	p.filterByInertia = true;
	p.minInertiaRatio = 0.2f;
	return cv::SimpleBlobDetector::create(p);
}

// A symmetric grid looks the same turned by 180 degrees, so OpenCV may
// start from either end; the top-left circle goes first in both cameras.
int findGrid(const cv::Mat &gray, GridSize grid, double minArea, double scale,
	     std::vector<ImagePoint> &centres)
{
	std::vector<cv::Point2f> found;
	auto detector = blobDetector(gray.cols, gray.rows, grid, minArea);
	if (!cv::findCirclesGrid(gray, cv::Size(grid.cols, grid.rows), found,
				 cv::CALIB_CB_SYMMETRIC_GRID, detector) ||
	    found.size() != static_cast<size_t>(grid.count()))
		return -ENOENT;

	const cv::Point2f &first = found.front(), &last = found.back();
	if (first.x + first.y > last.x + last.y)
		std::reverse(found.begin(), found.end());

	// Rows must run left to right: a pattern held upright in both cameras.
	cv::Point2f along = found[1] - found[0];
	if (std::abs(along.x) < std::abs(along.y))
		return -ENOENT;

	centres.clear();
	for (const cv::Point2f &p : found)
		centres.push_back({ (p.x + 0.5) / scale - 0.5, (p.y + 0.5) / scale - 0.5 });
	return 0;
}

double median(std::vector<double> &values)
{
	auto mid = values.begin() + static_cast<long>(values.size() / 2);
	std::nth_element(values.begin(), mid, values.end());
	return *mid;
}

} // namespace

Gray8Image amplitudeForDetection(const Gray16Image &amplitude)
{
	// Stretch between the 2nd and 98th percentile of the measured amplitudes:
	// the SR-2's amplitude falls with distance squared, so a fixed scale
	// would leave a far pattern black.
	std::vector<uint16_t> values;
	for (size_t i = 0; i < amplitude.size(); i++)
		if (amplitude.data()[i] > 0)
			values.push_back(amplitude.data()[i]);
	double lo = 0, hi = 1;
	if (!values.empty()) {
		auto at = [&](double q) {
			auto it = values.begin() + static_cast<long>(q * (values.size() - 1));
			std::nth_element(values.begin(), it, values.end());
			return static_cast<double>(*it);
		};
		lo = at(0.02);
		hi = std::max(at(0.98), lo + 1);
	}

	cv::Mat src(amplitude.height(), amplitude.width(), CV_16UC1,
		    const_cast<uint16_t *>(amplitude.data()));
	cv::Mat stretched, scaled;
	src.convertTo(stretched, CV_8UC1, 255.0 / (hi - lo), -lo * 255.0 / (hi - lo));
	cv::resize(stretched, scaled, cv::Size(), kAmplitudeScale, kAmplitudeScale, cv::INTER_CUBIC);
	// Half a ToF pixel of blur: the per-pixel noise would otherwise split a
	// circle's threshold contours into fragments.
	cv::GaussianBlur(scaled, scaled, cv::Size(), 0.5 * kAmplitudeScale);

	Gray8Image out(scaled.cols, scaled.rows);
	for (int y = 0; y < scaled.rows; y++)
		std::copy_n(scaled.ptr<uint8_t>(y), scaled.cols, out.row(y));
	return out;
}

int findColourGrid(const RgbImage &rgb, GridSize grid, std::vector<ImagePoint> &centres)
{
	cv::Mat src(rgb.height(), rgb.width(), CV_8UC3, const_cast<Rgb8 *>(rgb.data()));
	cv::Mat gray;
	cv::cvtColor(src, gray, cv::COLOR_RGB2GRAY);
	return findGrid(gray, grid, 12.0, 1.0, centres);
}

int findAmplitudeGrid(const Gray16Image &amplitude, GridSize grid, std::vector<ImagePoint> &centres)
{
	Gray8Image scaled = amplitudeForDetection(amplitude);
	cv::Mat gray(scaled.height(), scaled.width(), CV_8UC1, scaled.data());
	// A circle two ToF pixels across is the smallest that still has a centre.
	constexpr double kMinArea = 3.0 * kAmplitudeScale * kAmplitudeScale;
	return findGrid(gray, grid, kMinArea, kAmplitudeScale, centres);
}

double depthAround(const DepthFrame &depth, ImagePoint centre, double radiusPx)
{
	const Gray16Image &z = depth.depthMm;
	bool amplitude = depth.amplitude.width() == z.width() && depth.amplitude.height() == z.height();
	std::vector<double> depths, amplitudes;
	int x0 = std::max(0, static_cast<int>(std::floor(centre.x - radiusPx)));
	int x1 = std::min(z.width() - 1, static_cast<int>(std::ceil(centre.x + radiusPx)));
	int y0 = std::max(0, static_cast<int>(std::floor(centre.y - radiusPx)));
	int y1 = std::min(z.height() - 1, static_cast<int>(std::ceil(centre.y + radiusPx)));
	for (int y = y0; y <= y1; y++) {
		for (int x = x0; x <= x1; x++) {
			double dx = x - centre.x, dy = y - centre.y;
			if (dx * dx + dy * dy > radiusPx * radiusPx || z.at(x, y) == 0)
				continue;
			depths.push_back(z.at(x, y));
			amplitudes.push_back(amplitude ? depth.amplitude.at(x, y) : 0.0);
		}
	}
	if (depths.empty())
		return 0;

	// The black circle returns little light and so the noisiest depths; the
	// paper around it (amplitude above the local median) measures best.
	std::vector<double> sorted = amplitudes;
	double threshold = median(sorted);
	std::vector<double> bright;
	for (size_t i = 0; i < depths.size(); i++)
		if (amplitudes[i] >= threshold)
			bright.push_back(depths[i]);
	return median(bright.empty() ? depths : bright) / 1000.0;
}

int pairView(const ColourFrame &colour, const DepthFrame &depth, GridSize grid,
	     CalibrationView &view, std::string &error)
{
	std::vector<ImagePoint> inColour, inTof;
	bool colourSees = findColourGrid(colour.rgb, grid, inColour) == 0;
	bool tofSees = findAmplitudeGrid(depth.amplitude, grid, inTof) == 0;
	std::string pattern = std::to_string(grid.cols) + "x" + std::to_string(grid.rows) + " grid";
	if (!colourSees || !tofSees) {
		error = !colourSees && !tofSees ? "neither camera sees the whole " + pattern
			: !colourSees ? "the colour camera does not see the whole " + pattern
				      : "the ToF camera does not see the whole " + pattern +
						" in its amplitude image";
		return -ENOENT;
	}

	// Half the distance between neighbouring circles: the disc around a
	// centre that holds its circle and the paper around it, no other circle.
	double spacing = 0;
	for (int r = 0; r < grid.rows; r++)
		for (int c = 1; c < grid.cols; c++) {
			const ImagePoint &a = inTof[r * grid.cols + c - 1], &b = inTof[r * grid.cols + c];
			spacing += std::hypot(b.x - a.x, b.y - a.y);
		}
	spacing /= grid.rows * (grid.cols - 1);

	view.points.clear();
	std::vector<double> depths;
	for (int i = 0; i < grid.count(); i++) {
		double z = depthAround(depth, inTof[i], 0.5 * spacing);
		if (z <= 0) {
			error = "the ToF camera has no depth at circle " + std::to_string(i + 1) +
				" of the " + pattern;
			return -EINVAL;
		}
		view.points.push_back({ inTof[i].x, inTof[i].y, z, inColour[i].x, inColour[i].y });
		depths.push_back(z);
	}
	view.depthM = median(depths);
	return 0;
}

} // namespace depthkey
