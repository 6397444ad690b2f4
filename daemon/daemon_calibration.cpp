// What the daemon does with the calibration the pipeline maps depth with. A
// file that is missing or refused is reported (once, and again when it
// changes) and the daemon runs on its last good state: the previous
// calibration, or identity scaling when there never was one.
#include "daemon/daemon.hpp"

#include "daemon/log.hpp"
#include "wiring/pipeline_setup.hpp"

namespace depthkey {

// files were read for settings_ (on the reload worker, or at start).
void Daemon::applyPipelineFiles(const PipelineFiles &files)
{
	const std::string &path = settings_.mapping.calibrationFile;
	if (path.empty()) {
		calibrated_ = false;
		mapping_ = files.mapping;
		logger().errorOnce("calibration",
				   "no calibration file (mapping.calibration_file is empty): "
				   "depth is mapped to colour by plain scaling",
				   { { "DEVICE", "calibration" }, { "CALIBRATION_FILE", path } });
	} else if (!files.calibrated) {
		logger().errorOnce("calibration",
				   "calibration refused: " + files.calibrationError +
					   (calibrated_ ? "; keeping the previous calibration"
							: "; mapping by plain scaling"),
				   { { "DEVICE", "calibration" }, { "CALIBRATION_FILE", path } });
		if (!calibrated_)
			mapping_ = files.mapping;
	} else {
		mapping_ = files.mapping;
		calibrated_ = true;
		logger().clearError("calibration",
				    std::string("calibration loaded, model ") + mappingKindName(mapping_.kind) +
					    ", fitted for " + calibrationSizes(mapping_),
				    { { "DEVICE", "calibration" }, { "CALIBRATION_FILE", path } });
	}

	// The calibration file's board H goes with its mapping: a refused file
	// keeps the last good one of both (board_.apply/start reads it).
	if (path.empty() || files.calibrated)
		board_.setCalibrationFileBoard(files.boardCalibration);

	// The board picture is the board source's (its errors are its own).
	configurePipeline(pipeline_, settings_, mapping_, board_.pipelineBoard());
	pipelineStatus_ = pipeline_.status(); // between frames: the pipeline is the loop's
}

// On the status tick, once frames of both cameras have arrived: the
// pipeline falls back to plain scaling for frame sizes the calibration was
// not fitted for; the journal says so and why, once.
void Daemon::checkCalibrationFits()
{
	if (!calibrated_ || colourWidth_ == 0 || depthWidth_ == 0)
		return;
	std::string why = calibrationMismatch(mapping_, colourWidth_, colourHeight_, depthWidth_,
					      depthHeight_);
	const std::string &path = settings_.mapping.calibrationFile;
	if (!why.empty())
		logger().errorOnce("calibration_size", path + ": " + why,
				   { { "DEVICE", "calibration" }, { "CALIBRATION_FILE", path } });
	else
		logger().clearError("calibration_size", "calibration fits the frame sizes again",
				    { { "DEVICE", "calibration" }, { "CALIBRATION_FILE", path } });
}

CalibrationFacts Daemon::calibrationFacts() const
{
	CalibrationFacts f;
	const std::string &path = settings_.mapping.calibrationFile;
	f.depth = summary().calibrated;
	f.depthState = f.depth		  ? "calibrated (" + path + ")"
		       : path.empty()	  ? std::string("NOT calibrated (mapping.calibration_file is empty)")
		       : calibrated_	  ? "NOT calibrated: " + path + " was fitted for other frame sizes (journal)"
					  : "NOT calibrated: " + path + " is refused (journal, DEVICE=calibration)";
	f.board = board_.boardGeometry();
	f.boardState = board_.statusText();
	return f;
}

} // namespace depthkey
