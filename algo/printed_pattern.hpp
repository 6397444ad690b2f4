// The depth calibration pattern as printed on a sheet of paper
// (depthkey-calibrate --print-pattern): the grid of black circles that
// pairView looks for in both cameras, laid out at its true size on A4 or A3
// (or the simulator's A1) landscape, with room for a printer's unprintable
// border and a line of text that gives the spacing.
//
// The proportions are the simulator's board (hal/sim/calibration_pattern.hpp,
// 120 mm spacing, 70 mm circles): diameter 0.58 of the spacing (the
// detector's centre refinement wants at most 0.6), white paper of 0.42
// spacing beyond the outer circles. The spacing is the largest whole
// millimetre that fits, so that a ruler checks the print.
#pragma once

#include "algo/circle_grid_detector.hpp"

#include <string>

namespace depthkey {

struct PaperSize {
	const char *name;               // "a4"
	double widthMm, heightMm;       // landscape
};

// "a4", "a3", "a2", "a1"; nullptr for anything else.
const PaperSize *findPaperSize(const std::string &name);
// The names, for usage and errors: "a4|a3|a2|a1".
std::string paperSizeNames();

struct PrintedPattern {
	PaperSize paper{};
	GridSize grid;
	double spacingMm = 0;   // centre to centre, whole mm
	double diameterMm = 0;
	double originXMm = 0, originYMm = 0;    // the top-left circle's centre on the page
	double textBaselineMm = 0;              // the line that states the spacing

	// Circle (col, row)'s centre on the page, mm from the top left.
	double centreXMm(int col) const { return originXMm + col * spacingMm; }
	double centreYMm(int row) const { return originYMm + row * spacingMm; }
};

constexpr double kPrinterBorderMm = 10;      // left blank for the printer
constexpr double kTextLineMm = 12;           // the spacing's line under the grid
constexpr double kDiameterPerSpacing = 0.58;
constexpr double kPaperPerSpacing = 0.42;    // white beyond the outer circles

// The largest pattern of grid that fits paper; -EINVAL when the grid leaves
// a spacing under 10 mm (too small for the ToF camera at any depth).
int layoutPrintedPattern(const PaperSize &paper, GridSize grid, PrintedPattern &out);

} // namespace depthkey
