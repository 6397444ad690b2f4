// The board calibration file: the homography colour px -> board px that
// depthkey-calibrate --board fits and the daemon's board-geometry composite
// uses (board.homography_file).
//
// A file of its own, and optionally also a [board] section of the depth
// calibration file (depthkey-calibrate --sim writes one; the file of its
// own, when set, takes precedence). Of its own, because the two
// are made by different procedures (a pattern on the board's screen, a
// printed pattern held at five depths) and go stale for different reasons
// (the camera knocked against the board vs. the ToF bracket re-mounted), so
// a technician redoes one without rewriting, or risking, the other; and a
// box whose depth calibration is fine keeps it while the board is redone.
//
// TOML, every key required but the lens's (lens_k1, lens_k2: absent in the
// first files, which were fitted as a pinhole), nothing unknown allowed; a corrupt, partial or
// impossible file (a singular H) is refused with FILE:LINE:COLUMN: KEY:
// MESSAGE, and the daemon keeps its last good H. Written atomically, and
// only what the reader accepts.
#pragma once

#include "algo/homography.hpp"
#include "algo/radial_lens.hpp"
#include "config/config_error.hpp"

#include <string>
#include <string_view>
#include <vector>

namespace depthkey {

constexpr int kBoardCalibrationFormat = 1;

struct BoardCalibration {
	Homography colourToBoard;              // ideal (undistorted) colour px -> board px
	double lensK1 = 0, lensK2 = 0;         // the colour lens (algo/radial_lens.hpp)
	int colourWidth = 0, colourHeight = 0; // the colour image H was fitted in
	int boardWidth = 0, boardHeight = 0;   // the board picture's pixels
	std::string date;                      // UTC, "2024-05-01T12:00:00Z"
	int points = 0;                        // circles fitted on
	double rmsPx = 0, maxPx = 0;           // reprojection error, board px

	RadialLens lens() const { return RadialLens::forImage(colourWidth, colourHeight, lensK1, lensK2); }
};

struct BoardCalibrationResult {
	BoardCalibration calibration;   // meaningful only when ok()
	std::vector<ConfigError> errors;
	bool ok() const { return errors.empty(); }
};

BoardCalibrationResult loadBoardCalibration(const std::string &path);
// The [board] table alone, shared with the depth calibration file, which may
// carry one (config/calibration_file.hpp: depthkey-calibrate --sim writes it).
class TomlSection;
void bindBoardCalibrationSection(TomlSection &section, BoardCalibration &calibration);
std::string formatBoardCalibrationSection(const BoardCalibration &calibration);
BoardCalibrationResult parseBoardCalibration(std::string_view text, const std::string &sourceName);
std::string formatBoardCalibration(const BoardCalibration &calibration);
// -EINVAL (never written) when the reader would refuse it; else atomic.
int writeBoardCalibration(const std::string &path, const BoardCalibration &calibration, std::string &error);

} // namespace depthkey
