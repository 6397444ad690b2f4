// Where the technician holds the pattern, view by view: at several depths,
// and at each depth in the middle and towards the four corners of the image,
// so the fit sees every part of the image at every depth it uses.
#pragma once

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

} // namespace depthkey
