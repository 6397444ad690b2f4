// Finding the calibration pattern, a symmetric grid of black circles on
// white, in the colour image and in the ToF amplitude image, and pairing the
// circle centres of the two into the point pairs the fit needs.
//
// OpenCV's calib3d does the finding (findCirclesGrid with a SimpleBlobDetector).
// A 160x124 amplitude image shows each circle as a few noisy pixels, so it
// is stretched to 8 bits, scaled up 4 times and smoothed first, with the blob
// detector's area limits set for that scale.
#pragma once

#include <string>
#include <vector>

#include "algo/calibration_fit.hpp"
#include "algo/frames.hpp"

namespace depthkey {

struct GridSize {
	int cols = 7;           // circles per row
	int rows = 5;           // rows
	int count() const { return cols * rows; }
};

struct ImagePoint {
	double x = 0, y = 0;    // pixel i's centre at i
};

// The ToF amplitude image scaled up for detection and preview: 8 bits,
// kAmplitudeScale times the size, the circles dark.
constexpr int kAmplitudeScale = 4;
Gray8Image amplitudeForDetection(const Gray16Image &amplitude);

// Circle centres, row by row from the top-left circle, or -ENOENT when the
// whole grid is not in the image. Both cameras see the pattern upright, so
// the order is the same in both images. -E2BIG when the image holds more
// than 4 circle-like blobs for each circle of the grid (clutter or noise):
// the search for the grid among them would grow as the cube of their
// count, so it is not made. The work is bounded whatever the image shows:
// a frame wider than 1024 px is searched for blobs at a fraction of its
// size (the centres refined at full size).
int findColourGrid(const RgbImage &rgb, GridSize grid, std::vector<ImagePoint> &centres);
int findAmplitudeGrid(const Gray16Image &amplitude, GridSize grid, std::vector<ImagePoint> &centres);

// Why the whole grid was not found in one camera's image, for the
// technician: how many circles the detector saw; whether whole columns or
// rows are missing beside the image's edge (the grid is cut there) or
// circles are missing elsewhere (hidden, or too small); or whether all are
// there but not in the grid's shape.
struct GridMiss {
	enum class Kind { Found, NoCircles, Cut, Hidden, TooMany, NotAGrid } kind = Kind::Found;
	int circles = 0;             // dark round blobs the detector saw
	bool countIsFloor = false;   // TooMany counted no further than circles
	int expected = 0;            // grid.count()
	std::string edges;           // "left", "top and right"...: where blobs touch the border
	// "25 of 35 circles found, whole columns are missing at the image's left edge: ...".
	std::string describe() const;
	// The same without the count: a live view says it again only when this changes.
	std::string reason() const;
};
GridMiss explainColourMiss(const RgbImage &rgb, GridSize grid);
GridMiss explainAmplitudeMiss(const Gray16Image &amplitude, GridSize grid);

// The pattern's depth at a ToF circle centre: the median of the valid depths
// around it (within radiusPx), taken from the bright paper between circles
// when there is some, where the ToF measures best. 0 when none is valid.
double depthAround(const DepthFrame &depth, ImagePoint centre, double radiusPx);

// Both cameras' view of the pattern as point pairs, labelled with depthM.
// Returns -ENOENT with error naming the camera that did not see the whole
// grid and why (GridMiss), -E2BIG naming the camera that sees too many
// blobs, or -EINVAL when the depth image has no depth at the circles.
int pairView(const ColourFrame &colour, const DepthFrame &depth, GridSize grid,
	     CalibrationView &view, std::string &error);

} // namespace depthkey
