// What the pipeline needs from files: the calibration (mapping) and the board
// image. A file that is missing or refused is reported (once, and again when
// it changes) and the daemon runs on its last good state: the previous
// calibration, or identity scaling when there never was one; the solid board
// colour instead of a missing board image.
#include "daemon/daemon.hpp"

#include "config/calibration_file.hpp"
#include "daemon/log.hpp"
#include "hal/image_file.hpp"

namespace depthkey {

namespace {

// SR-2 resolution; the pipeline rescales identity to whatever sizes arrive.
MappingModel identityMapping(const Settings &settings)
{
	MappingModel model;
	model.colourWidth = settings.colour.width;
	model.colourHeight = settings.colour.height;
	return model;
}

// The journal line names the first problem; `depthkey-calibrate` or a look at
// the file shows the rest.
std::string moreErrors(size_t count)
{
	return count > 1 ? " (and " + std::to_string(count - 1) + " more)" : std::string();
}

} // namespace

void Daemon::configurePipeline()
{
	const std::string &path = settings_.mapping.calibrationFile;
	if (path.empty()) {
		calibrated_ = false;
		mapping_ = identityMapping(settings_);
		logger().errorOnce("calibration",
				   "no calibration file (mapping.calibration_file is empty): "
				   "depth is mapped to colour by plain scaling",
				   { { "DEVICE", "calibration" }, { "CALIBRATION_FILE", path } });
	} else {
		CalibrationResult result = loadCalibration(path);
		if (!result.ok()) {
			logger().errorOnce("calibration",
					   "calibration refused: " + result.errors.front().toString() +
						   moreErrors(result.errors.size()) +
						   (calibrated_ ? "; keeping the previous calibration"
								: "; mapping by plain scaling"),
					   { { "DEVICE", "calibration" }, { "CALIBRATION_FILE", path } });
			if (!calibrated_)
				mapping_ = identityMapping(settings_);
		} else {
			mapping_ = result.calibration.mapping;
			calibrated_ = true;
			logger().clearError("calibration",
					    std::string("calibration loaded, model ") +
						    mappingKindName(mapping_.kind),
					    { { "DEVICE", "calibration" }, { "CALIBRATION_FILE", path } });
		}
	}

	RgbImage board;
	const std::string &boardPath = settings_.composite.boardImage;
	if (!boardPath.empty()) {
		std::string error;
		if (readRgbImage(boardPath, board, error) < 0) {
			board = RgbImage();
			logger().errorOnce("board_image", "board image unusable, showing board_colour: " + error,
					   { { "DEVICE", "board_image" } });
		} else {
			logger().clearError("board_image", "board image loaded", { { "DEVICE", "board_image" } });
		}
	}
	pipeline_.setBoardImage(board);
	pipeline_.configure(settings_, mapping_);
}

} // namespace depthkey
