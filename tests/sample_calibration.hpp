// A complete, valid calibration for tests (two models, three depths).
#pragma once

#include "config/calibration_file.hpp"

namespace depthkey::test {

inline Calibration sampleCalibration()
{
	Calibration c;
	c.mapping.kind = MappingKind::Parallax;
	for (int i = 0; i < kMappingCoefficients; i++) {
		c.mapping.x[i] = 0.1 * i - 0.3 + (i == 0 ? 319.5 : 0.0);
		c.mapping.y[i] = 1.0 / (i + 3.0) + (i == 0 ? 239.5 : 0.0);
	}
	c.date = "2024-05-01T12:00:00Z";
	c.colourCamera = "sim colour \"front\" 640x480";
	c.tofCamera = "sim tof 160x124";
	c.selectedBy = "heldout";
	c.heldOutViews = "every 4th view";
	c.depthsM = { 0.8, 1.4, 2.0 };
	for (MappingKind kind : { MappingKind::Paper, MappingKind::Parallax }) {
		c.summaries.push_back({ kind, { 100, 0.3, 1.1 }, { 25, 0.4, 1.3 } });
		for (double depth : c.depthsM) {
			c.residuals.push_back({ kind, false, depth, { 30, 0.25, 0.9 } });
			c.residuals.push_back({ kind, true, depth, { 8, 0.35, 1.0 } });
		}
	}
	return c;
}

// A valid board calibration (the simulated room's, 640x480 colour, 1920x780
// board), for the board file and the calibration file's [board].
inline BoardCalibration sampleBoardCalibration()
{
	BoardCalibration c;
	c.colourToBoard.h = { 1.99998, -1.5e-05, 320.504, -4.38e-06, 1.99998, -11.4965, -1.1e-08, -9.9e-09, 1 };
	c.colourWidth = 640;
	c.colourHeight = 480;
	c.boardWidth = 1920;
	c.boardHeight = 780;
	c.date = "2026-12-01T17:00:00Z";
	c.points = 45;
	c.rmsPx = 0.0123;
	c.maxPx = 0.05;
	return c;
}

} // namespace depthkey::test
