// What the pipeline needs from files: the calibration (mapping) and the board
// image, read and applied alike by depthkeyd and depthkey-eval.
#include "wiring/pipeline_setup.hpp"

#include "config/calibration_file.hpp"
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
			files.boardCalibration = result.calibration.board;
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
	pipeline.configure(PipelineSettings::from(settings), mapping);
}

} // namespace depthkey
