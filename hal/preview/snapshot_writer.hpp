// Stage snapshots: PNG files of what the pipeline saw and made, for a
// technician tuning the config (SIGUSR1 with daemon.snapshot_dir, depthkeyd
// --preview, depthkey-eval --preview).
#pragma once

#include "algo/stage_images.hpp"

#include <string>

namespace depthkey {

// Writes one PNG per stage into dir (created if missing), named
// prefix + stage name + ".png": colour as is, depth in false colour (near
// red, far blue, no measurement black; 0.5..4 m), seeds in three colours
// (lecturer orange, board blue, undecided grey), masks in grey. Small depth
// images are enlarged 4x (nearest) to be seen. Empty images are skipped.
// Returns 0 or a negative errno with error naming the file.
int writeStageImages(const std::string &dir, const std::string &prefix, const StageImages &stages,
		     std::string &error);

} // namespace depthkey
