// What the pipeline needs from files: the calibration (mapping) and the board
// image. A file that is missing or refused is reported (once, and again when
// it changes) and the daemon runs on its last good state: the previous
// calibration, or identity scaling when there never was one; the solid board
// colour instead of a missing board image.
#include "daemon/pipeline_setup.hpp"

#include "config/calibration_file.hpp"
#include "daemon/daemon.hpp"
#include "daemon/log.hpp"
#include "hal/image_file.hpp"
#include "hal/kernel_path_env.hpp"

namespace depthkey {

namespace {

// The journal line names the first problem; `depthkey-calibrate` or a look at
// the file shows the rest.
std::string moreErrors(size_t count)
{
	return count > 1 ? " (and " + std::to_string(count - 1) + " more)" : std::string();
}

} // namespace

std::string calibrationSizes(const MappingModel &m)
{
	return "colour " + std::to_string(m.colourWidth) + "x" + std::to_string(m.colourHeight) +
	       " and depth " + std::to_string(m.tofWidth) + "x" + std::to_string(m.tofHeight);
}

std::string calibrationMismatch(const MappingModel &m, int colourWidth, int colourHeight,
				int depthWidth, int depthHeight)
{
	if (m.colourWidth == colourWidth && m.colourHeight == colourHeight &&
	    m.tofWidth == depthWidth && m.tofHeight == depthHeight)
		return "";
	MappingModel frames;
	frames.colourWidth = colourWidth;
	frames.colourHeight = colourHeight;
	frames.tofWidth = depthWidth;
	frames.tofHeight = depthHeight;
	return "the calibration was fitted for " + calibrationSizes(m) + " but the cameras deliver " +
	       calibrationSizes(frames) +
	       ": depth is mapped by plain scaling; calibrate again for these sizes "
	       "(or set the cameras' width and height back)";
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

// SR-2 resolution; the pipeline rescales identity to whatever sizes arrive.
MappingModel identityMapping(const Settings &settings)
{
	MappingModel model;
	model.colourWidth = settings.colour.width;
	model.colourHeight = settings.colour.height;
	return model;
}

PipelineFiles loadPipelineFiles(const Settings &settings)
{
	PipelineFiles files;
	files.mapping = identityMapping(settings);
	if (!settings.mapping.calibrationFile.empty()) {
		CalibrationResult result = loadCalibration(settings.mapping.calibrationFile);
		if (result.ok()) {
			files.mapping = result.calibration.mapping;
			files.calibrated = true;
		} else {
			files.calibrationError = result.errors.front().toString() + moreErrors(countErrors(result.errors));
		}
	}
	// The daemon's board comes from its board source (daemon/board_output.hpp);
	// the eval composites over a board image when one is configured.
	if (settings.board.backend == "image" && !settings.board.image.empty() &&
	    readRgbImage(settings.board.image, files.board, files.boardError) < 0)
		files.board = RgbImage();
	return files;
}

void configurePipeline(Pipeline &pipeline, const Settings &settings, const MappingModel &mapping,
		       const RgbImage &board)
{
	pipeline.setKernelPath(kernelPathFromEnvironment());
	pipeline.setBoardImage(board);
	pipeline.configure(settings, mapping);
}

// files were read for settings_ (on the reload worker, or at start).
void Daemon::configurePipeline(const PipelineFiles &files)
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

	// The board picture is the board source's (its errors are its own).
	depthkey::configurePipeline(pipeline_, settings_, mapping_,
				    board_.boardGeometry() ? RgbImage() : board_.picture());
}

} // namespace depthkey
