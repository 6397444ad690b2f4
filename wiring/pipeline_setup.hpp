// What the pipeline and the frame pairer are configured from, shared by
// depthkeyd (Daemon::applyPipelineFiles, daemon/daemon_calibration.cpp) and
// depthkey-eval, so that the two never run them differently.
#pragma once

#include "algo/frame_pairer.hpp"
#include "algo/pairing_queue.hpp"
#include "algo/mapping_model.hpp"
#include "algo/pipeline.hpp"
#include "config/board_calibration_file.hpp"
#include "settings/settings.hpp"

#include <optional>
#include <string>

namespace depthkey {

// "colour 640x480 and depth 176x144": what a calibration was fitted for.
std::string calibrationSizes(const MappingModel &mapping);
// "" when mapping fits these frame sizes, else a sentence saying what was
// fitted, what arrives, and what to do.
std::string calibrationMismatch(const MappingModel &mapping, int colourWidth, int colourHeight,
				int depthWidth, int depthHeight);

// Plain scaling of depth onto colour: the mapping without a calibration.
MappingModel identityMapping(const Settings &settings);

// The files the pipeline reads: the calibration's mapping (identity when
// none is set or it is refused) and the board image (empty = board colour).
struct PipelineFiles {
	MappingModel mapping;
	bool calibrated = false;
	RgbImage board;
	// The calibration file's [board] section, if it has one (used when
	// board.homography_file is empty).
	std::optional<BoardCalibration> boardCalibration;
	std::string calibrationError, boardError; // "" when fine
};
PipelineFiles loadPipelineFiles(const Settings &settings);

// The one call that configures the pipeline, for the daemon and the eval.
void configurePipeline(Pipeline &pipeline, const Settings &settings, const MappingModel &mapping,
		       const RgbImage &board);

// offsetNs: the depth offset in force (pairing.offset_ms, or the measured
// latency when it is "auto").
inline void configurePairingQueue(PairingQueue &queue, const Settings &settings, int64_t offsetNs)
{
	const uint64_t delayNs = uint64_t(settings.pairing.delayMs) * 1'000'000;
	queue.configure(offsetNs, uint64_t(settings.pairing.maxSkewMs) * 1'000'000, delayNs,
			PairingQueue::slotsFor(delayNs, settings.colour.fps));
}

} // namespace depthkey
