// The calibration file: the depth -> colour mapping that depthkey-calibrate
// fits and the daemon applies, with what it was fitted on and how well.
//
// TOML, every key required, nothing unknown allowed (docs/calibration-file.md
// documents each key). The reader refuses a file that is corrupt,
// partial or inconsistent with an error naming file:line:column and key, so
// the daemon keeps its last good mapping. The writer only writes what the
// reader accepts, and replaces the file atomically.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "algo/calibration_fit.hpp"
#include "config/board_calibration_file.hpp"
#include "config/config_error.hpp"

namespace depthkey {

constexpr int kCalibrationFormat = 1;

struct Calibration {
	MappingModel mapping;           // kind, image sizes and coefficients
	std::string date;               // UTC, "2024-05-01T12:00:00Z"
	std::string colourCamera;       // which cameras: a box recalibrates when one changes
	std::string tofCamera;
	std::string selectedBy;         // "heldout" (lowest held-out error) or "option" (--model)
	std::string heldOutViews;       // how views were held out, e.g. "every 4th view"
	std::vector<double> depthsM;    // the pattern's depths fitted on, ascending
	std::vector<CalibrationSummary> summaries;      // one per model fitted
	std::vector<CalibrationResidual> residuals;     // per model, set and depth
	// The board's homography, when the same session calibrated the board
	// (depthkey-calibrate --sim does: the simulated room in one go). The
	// daemon uses it when board.homography_file is empty; a board file of
	// its own (depthkey-calibrate --board) takes precedence.
	std::optional<BoardCalibration> board;
};

struct CalibrationResult {
	Calibration calibration;        // meaningful only when ok()
	std::vector<ConfigError> errors;        // in file order
	bool ok() const { return errors.empty(); }
};

// The calibration in path; a missing or unreadable file is an error naming it.
CalibrationResult loadCalibration(const std::string &path);

// sourceName is the file name the errors carry.
CalibrationResult parseCalibration(std::string_view text, const std::string &sourceName);

// The file's text; coefficients are written so they read back bit for bit.
std::string formatCalibration(const Calibration &calibration);

// Checks that the reader accepts the calibration, then replaces path
// atomically. A calibration the reader would refuse is never written, so a
// good file is never replaced by a bad one. Returns 0 or a negative errno
// (-EINVAL for a refused calibration) with error saying why.
int writeCalibration(const std::string &path, const Calibration &calibration, std::string &error);

} // namespace depthkey
