// Circle-grid detection in both cameras with OpenCV, and the pairing.
#include "algo/circle_grid_detector.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <limits>

#include <opencv2/calib3d.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include <Eigen/Dense>

namespace depthkey {

namespace {

// The smallest blob a circle may be, in the searched image's pixels: in the
// colour image 12; in the amplitude image (scaled up kAmplitudeScale times)
// a circle two ToF pixels across, the smallest that still has a centre.
constexpr double kColourMinArea = 12.0;
constexpr double kAmplitudeMinArea = 3.0 * kAmplitudeScale * kAmplitudeScale;

// Blob limits for an image of the given size: a circle covers at least a
// few pixels and at most the whole grid's share of the image. Circularity and
// convexity are loosened so a pattern tilted by 45 degrees (ellipses) and a
// noisy ToF edge still pass.
cv::SimpleBlobDetector::Params blobParams(int width, int height, GridSize grid, double minArea)
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
	return p;
}

// Bounds on the work (issue 31 point 12). OpenCV's grid search over the
// blobs grows about as the cube of their count (520 blobs 1 s, 2120 blobs
// 71 s on a 640x480 frame of dots), so a frame with more blobs than a
// pattern and some clutter could give is refused before the search; and a
// large frame is searched for blobs at most kMaxDetectionWidth wide (the
// centres are refined at full size afterwards), so that the blob detector's
// thresholds cost the same whatever the camera.
constexpr int kBlobsPerCircle = 4;
constexpr int kMaxDetectionWidth = 1024;

size_t maxBlobs(GridSize grid)
{
	return static_cast<size_t>(kBlobsPerCircle * grid.count());
}

// The blob detector's own cost grows with the dark patches at each of its
// thresholds (2.8 s for 1080p noise at half size), before any shape test.
// Connected components at the same thresholds, counted by area alone, cost
// a few ms each: a threshold with more than kCandidatesPerCircle patches of
// a circle's size for each circle is clutter or noise, refused before the
// detector runs. The middle thresholds go first: there such a frame shows
// the most patches, so it is refused after one or two.
constexpr int kCandidatesPerCircle = 64;

bool tooManyPatches(const cv::Mat &gray, const cv::SimpleBlobDetector::Params &p, GridSize grid)
{
	const size_t limit = static_cast<size_t>(kCandidatesPerCircle * grid.count());
	std::vector<float> thresholds;
	for (float t = p.minThreshold; t < p.maxThreshold; t += p.thresholdStep)
		thresholds.push_back(t);
	const float middle = (p.minThreshold + p.maxThreshold) / 2;
	std::sort(thresholds.begin(), thresholds.end(),
		  [&](float a, float b) { return std::abs(a - middle) < std::abs(b - middle); });
	cv::Mat dark, labels, stats, centroids;
	for (float t : thresholds) {
		cv::threshold(gray, dark, t, 255, cv::THRESH_BINARY_INV);
		const int n = cv::connectedComponentsWithStats(dark, labels, stats, centroids, 8, CV_32S);
		size_t patches = 0;
		for (int i = 1; i < n; i++) {
			const int area = stats.at<int>(i, cv::CC_STAT_AREA);
			if (area >= p.minArea && area <= p.maxArea && ++patches > limit)
				return true;
		}
	}
	return false;
}

// A symmetric grid looks the same turned by 180 degrees, so OpenCV may
// start from either end; the top-left circle goes first in both cameras.
// scale: gray's pixels per pixel of the image the centres are given in.
int findGrid(const cv::Mat &gray, GridSize grid, double minArea, double scale,
	     std::vector<ImagePoint> &centres)
{
	const cv::SimpleBlobDetector::Params params = blobParams(gray.cols, gray.rows, grid, minArea);
	if (tooManyPatches(gray, params, grid))
		return -E2BIG;
	std::vector<cv::KeyPoint> blobs;
	cv::SimpleBlobDetector::create(params)->detect(gray, blobs);
	if (blobs.size() > maxBlobs(grid))
		return -E2BIG;
	if (blobs.size() < static_cast<size_t>(grid.count()))
		return -ENOENT;
	std::vector<cv::Point2f> points, found;
	for (const cv::KeyPoint &blob : blobs)
		points.push_back(blob.pt);
	// No detector: findCirclesGrid takes the blobs' centres as they are.
	if (!cv::findCirclesGrid(points, cv::Size(grid.cols, grid.rows), found, cv::CALIB_CB_SYMMETRIC_GRID,
				 cv::Ptr<cv::FeatureDetector>()) ||
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

// Mean distance between neighbouring centres along the rows (step 1) or
// the columns (step grid.cols).
double gridSpacing(const std::vector<ImagePoint> &c, GridSize grid, bool columns)
{
	int step = columns ? grid.cols : 1;
	double sum = 0;
	int n = 0;
	for (int i = 0; i + step < grid.count(); i++) {
		if (!columns && (i + 1) % grid.cols == 0)
			continue;
		sum += std::hypot(c[i + step].x - c[i].x, c[i + step].y - c[i].y);
		n++;
	}
	return sum / n;
}

// The blob detector's centres come from threshold contours, which a
// brightness gradient across a circle (the ToF's vignetting and distance
// fall-off, uneven room light) pulls towards the darker side: a scale error
// of a few tenths of a pixel at the image edges. Each centre is refined as
// the centroid of the circle's darkness below the paper around it, the
// paper's brightness fitted as a plane to the ring between the circle and
// its neighbours, so a linear gradient cancels, and the darkness taken
// relative to that paper.
template<typename Pixel>
void refineCentres(const cv::Mat &image, GridSize grid, std::vector<ImagePoint> &centres)
{
	// In units of the spacing along each axis (the SR-2's pixels are not
	// square): the circle (diameter at most 0.6 of the spacing) lies within
	// kInner, the ring out to kOuter is paper only.
	constexpr double kInner = 0.36, kOuter = 0.46;
	double sx = gridSpacing(centres, grid, false), sy = gridSpacing(centres, grid, true);
	for (ImagePoint &c : centres) {
		int x0 = std::max(0, static_cast<int>(std::floor(c.x - kOuter * sx)));
		int x1 = std::min(image.cols - 1, static_cast<int>(std::ceil(c.x + kOuter * sx)));
		int y0 = std::max(0, static_cast<int>(std::floor(c.y - kOuter * sy)));
		int y1 = std::min(image.rows - 1, static_cast<int>(std::ceil(c.y + kOuter * sy)));
		auto radius = [&](double dx, double dy) { return std::hypot(dx / sx, dy / sy); };

		// Plane a + b dx + c dy through the ring's pixels.
		Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
		Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
		for (int y = y0; y <= y1; y++)
			for (int x = x0; x <= x1; x++) {
				double dx = x - c.x, dy = y - c.y, r = radius(dx, dy);
				if (r < kInner || r > kOuter)
					continue;
				Eigen::Vector3d row(1.0, dx, dy);
				normal += row * row.transpose();
				rhs += row * static_cast<double>(image.at<Pixel>(y, x));
			}
		if (std::abs(normal.determinant()) < 1e-9)
			continue;
		Eigen::Vector3d plane = normal.ldlt().solve(rhs);

		double sum = 0, mx = 0, my = 0;
		for (int y = y0; y <= y1; y++)
			for (int x = x0; x <= x1; x++) {
				double dx = x - c.x, dy = y - c.y;
				if (radius(dx, dy) > kInner)
					continue;
				// Relative darkness: ink reflects a fixed share of what
				// paper would, so the weight is even across the circle
				// whatever the light falling on it.
				double paper = plane(0) + plane(1) * dx + plane(2) * dy;
				if (paper <= 0)
					continue;
				double dark = 1.0 - static_cast<double>(image.at<Pixel>(y, x)) / paper;
				sum += dark;
				mx += dark * dx;
				my += dark * dy;
			}
		if (sum <= 0)
			continue;
		c.x += mx / sum;
		c.y += my / sum;
	}
}

double median(std::vector<double> &values)
{
	auto mid = values.begin() + static_cast<long>(values.size() / 2);
	std::nth_element(values.begin(), mid, values.end());
	return *mid;
}

// The detector's blobs in the image it searched (scale: its size over the
// camera's), classified against what findGrid wanted.
// Distinct positions among values, those closer than gap counted as one:
// the columns (or rows) of a grid held roughly upright.
int distinctLines(std::vector<float> values, float gap)
{
	std::sort(values.begin(), values.end());
	int lines = values.empty() ? 0 : 1;
	for (size_t i = 1; i < values.size(); i++)
		lines += values[i] - values[i - 1] > gap;
	return lines;
}

GridMiss explainMiss(const cv::Mat &gray, GridSize grid, double minArea)
{
	GridMiss miss;
	miss.expected = grid.count();
	// Bounded as the search is (issue 31 point 12): --live asks on its loop
	// every half second, whatever the frame shows.
	const cv::SimpleBlobDetector::Params params = blobParams(gray.cols, gray.rows, grid, minArea);
	if (tooManyPatches(gray, params, grid)) {
		miss.kind = GridMiss::Kind::TooMany;
		miss.circles = kCandidatesPerCircle * grid.count();
		miss.countIsFloor = true;
		return miss;
	}
	std::vector<cv::KeyPoint> blobs;
	cv::SimpleBlobDetector::create(params)->detect(gray, blobs);
	miss.circles = static_cast<int>(blobs.size());
	if (blobs.empty()) {
		miss.kind = GridMiss::Kind::NoCircles;
		return miss;
	}
	if (miss.circles > miss.expected) {
		miss.kind = GridMiss::Kind::TooMany;
		return miss;
	}
	if (miss.circles == miss.expected) {
		miss.kind = GridMiss::Kind::NotAGrid;
		return miss;
	}
	// The grid's spacing in this image: the median distance from a blob to
	// its nearest neighbour (a lone blob: twice its size).
	std::vector<double> nearest;
	std::vector<float> xs, ys;
	for (const cv::KeyPoint &a : blobs) {
		double d = std::numeric_limits<double>::max();
		for (const cv::KeyPoint &b : blobs)
			if (&a != &b)
				d = std::min(d, static_cast<double>(cv::norm(a.pt - b.pt)));
		nearest.push_back(d);
		xs.push_back(a.pt.x);
		ys.push_back(a.pt.y);
	}
	double spacing = blobs.size() > 1 ? median(nearest) : 2.0 * blobs[0].size;
	// Whole columns or rows missing, the rest a full rectangle, next to the
	// image's border: the grid runs out of the picture there (a circle cut
	// by the edge is no blob: it fails the circularity test). Missing
	// circles anywhere else are hidden, or too small to be found.
	int cols = distinctLines(xs, static_cast<float>(spacing / 2));
	int rows = distinctLines(ys, static_cast<float>(spacing / 2));
	bool rectangle = cols * rows == miss.circles && cols >= 2 && rows >= 2 && cols <= grid.cols && rows <= grid.rows;
	float reach = static_cast<float>(1.5 * spacing);
	bool left = false, right = false, top = false, bottom = false;
	for (const cv::KeyPoint &b : blobs) {
		left |= cols < grid.cols && b.pt.x < reach;
		right |= cols < grid.cols && b.pt.x > gray.cols - 1 - reach;
		top |= rows < grid.rows && b.pt.y < reach;
		bottom |= rows < grid.rows && b.pt.y > gray.rows - 1 - reach;
	}
	std::vector<std::string> sides;
	for (auto [cut, name] : { std::pair{ left, "left" }, { right, "right" }, { top, "top" }, { bottom, "bottom" } })
		if (cut)
			sides.push_back(name);
	if (!rectangle || sides.empty()) {
		miss.kind = GridMiss::Kind::Hidden;
		return miss;
	}
	for (size_t i = 0; i < sides.size(); i++)
		miss.edges += (i == 0 ? "" : i + 1 == sides.size() ? " and " : ", ") + sides[i];
	miss.kind = GridMiss::Kind::Cut;
	return miss;
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
	// A 1080p frame is searched at half size: a circle of the smallest
	// area (12 px) keeps 3 px there, and the refinement below works on
	// every pixel.
	const int shrink = (gray.cols + kMaxDetectionWidth - 1) / kMaxDetectionWidth;
	cv::Mat small = gray;
	if (shrink > 1)
		cv::resize(gray, small, cv::Size(gray.cols / shrink, gray.rows / shrink), 0, 0, cv::INTER_AREA);
	const double scale = static_cast<double>(small.cols) / gray.cols;
	if (int ret = findGrid(small, grid, kColourMinArea * scale * scale, scale, centres); ret < 0)
		return ret;
	refineCentres<uint8_t>(gray, grid, centres);
	return 0;
}

int findAmplitudeGrid(const Gray16Image &amplitude, GridSize grid, std::vector<ImagePoint> &centres)
{
	Gray8Image scaled = amplitudeForDetection(amplitude);
	cv::Mat gray(scaled.height(), scaled.width(), CV_8UC1, scaled.data());
	if (int ret = findGrid(gray, grid, kAmplitudeMinArea, kAmplitudeScale, centres); ret < 0)
		return ret;
	// Refined on the measured amplitudes, not the stretched 8-bit copy.
	cv::Mat raw(amplitude.height(), amplitude.width(), CV_16UC1, const_cast<uint16_t *>(amplitude.data()));
	refineCentres<uint16_t>(raw, grid, centres);
	return 0;
}

std::string GridMiss::reason() const
{
	switch (kind) {
	case Kind::Found:
		return "the whole grid is seen";
	case Kind::NoCircles:
		return "no circle found: the pattern is out of view, too far, or too dark";
	case Kind::Cut:
		return "whole " + std::string(edges.find("left") != std::string::npos || edges.find("right") != std::string::npos
						      ? "columns"
						      : "rows") +
		       " are missing at the image's " + edges + " edge: the grid runs out of the picture there, "
		       "move the pattern towards the middle";
	case Kind::Hidden:
		return "not whole columns or rows at the image's edge: the rest are hidden (by the desk, a monitor, "
		       "a hand?), or too small to see";
	case Kind::TooMany:
		return "other dark round things are in view, or the circles are too small to tell apart";
	case Kind::NotAGrid:
		return "but not as a grid: hold the pattern upright, facing the camera";
	}
	return {};
}

std::string GridMiss::describe() const
{
	if (kind == Kind::Found || kind == Kind::NoCircles)
		return reason();
	if (kind == Kind::TooMany)
		return (countIsFloor ? "over " : "") + std::to_string(circles) + " circle-like blobs for the " +
		       std::to_string(expected) + " circles, " + reason();
	return std::to_string(circles) + " of " + std::to_string(expected) + " circles found, " + reason();
}

GridMiss explainColourMiss(const RgbImage &rgb, GridSize grid)
{
	cv::Mat src(rgb.height(), rgb.width(), CV_8UC3, const_cast<Rgb8 *>(rgb.data()));
	cv::Mat gray;
	cv::cvtColor(src, gray, cv::COLOR_RGB2GRAY);
	// As findColourGrid searches: at most kMaxDetectionWidth wide. Where
	// blobs touch the border is the same at any scale.
	const int shrink = (gray.cols + kMaxDetectionWidth - 1) / kMaxDetectionWidth;
	if (shrink > 1)
		cv::resize(gray, gray, cv::Size(gray.cols / shrink, gray.rows / shrink), 0, 0, cv::INTER_AREA);
	return explainMiss(gray, grid, kColourMinArea / (shrink * shrink));
}

GridMiss explainAmplitudeMiss(const Gray16Image &amplitude, GridSize grid)
{
	Gray8Image scaled = amplitudeForDetection(amplitude);
	cv::Mat gray(scaled.height(), scaled.width(), CV_8UC1, scaled.data());
	return explainMiss(gray, grid, kAmplitudeMinArea);
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
	const int colourRet = findColourGrid(colour.rgb, grid, inColour);
	const int tofRet = findAmplitudeGrid(depth.amplitude, grid, inTof);
	std::string pattern = std::to_string(grid.cols) + "x" + std::to_string(grid.rows) + " grid";
	if (colourRet == -E2BIG || tofRet == -E2BIG) {
		error = std::string(colourRet == -E2BIG ? "the colour camera" : "the ToF camera") + " sees more than " +
			std::to_string(maxBlobs(grid)) + " circle-like blobs (" + std::to_string(kBlobsPerCircle) +
			" for each circle of the " + pattern + "): clutter or noise, not searched for the pattern";
		return -E2BIG;
	}
	const bool colourSees = colourRet == 0, tofSees = tofRet == 0;
	if (!colourSees || !tofSees) {
		std::string colourWhy = colourSees ? "" : explainColourMiss(colour.rgb, grid).describe();
		std::string tofWhy = tofSees ? "" : explainAmplitudeMiss(depth.amplitude, grid).describe();
		error = !colourSees && !tofSees ? "neither camera sees the whole " + pattern + ": colour: " + colourWhy +
							  "; ToF amplitude: " + tofWhy
			: !colourSees ? "the colour camera does not see the whole " + pattern + ": " + colourWhy
				      : "the ToF camera does not see the whole " + pattern + " in its amplitude image: " +
						tofWhy;
		return -ENOENT;
	}

	// Half the distance between neighbouring circles: the disc around a
	// centre that holds its circle and the paper around it, no other circle.
	double spacing = gridSpacing(inTof, grid, false);

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
