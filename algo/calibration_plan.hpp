// Where the technician holds the pattern, view by view: at several depths,
// and at each depth in the middle and towards the four corners of the image,
// so the fit sees every part of the image at every depth it uses.
#pragma once

#include "algo/image.hpp"

#include <string>
#include <vector>

namespace depthkey {

struct PatternStep {
	double depthM = 0;      // pattern's distance from the colour camera
	int across = 0;         // -1 left, 0 middle, +1 right of the image
	int down = 0;           // -1 top, 0 middle, +1 bottom
	std::string where() const;      // "top left", "middle"...
};

// Depths the tool asks for by default: the near end of the working range is
// where the parallax changes fastest, so the steps are denser there.
std::vector<double> defaultCalibrationDepths();

// Each depth: middle, top left, top right, bottom left, bottom right.
std::vector<PatternStep> calibrationPlan(const std::vector<double> &depthsM);

// The far surface of the room as the ToF camera sees it before the pattern
// comes (the board, the wall behind it): the 75th percentile of the measured
// depths, in mm, so that the desk and a monitor in front of it do not count.
// 0 when under a tenth of the pixels measured anything (0 = no measurement).
int farSurfaceMm(const Gray16Image &depthMm);

// The depths at which the pattern can be held in front of that surface,
// clearanceM or more before it: a view asked for behind the board can only
// time out (on make run's simulated room, whose board stands 2 m away, the
// default plan's 2.0 and 2.5 m views were 10 of its 14 rejections).
std::vector<double> depthsInFrontOf(const std::vector<double> &depthsM, double surfaceM, double clearanceM);

} // namespace depthkey
