// Stage snapshots: PNG files of what the pipeline saw and made, for a
// technician tuning the config (SIGUSR1 with daemon.snapshot_dir set).
#pragma once

#include "algo/image.hpp"

#include <string>

namespace depthkey {

struct SnapshotImages {
	const RgbImage &colour;
	const Gray16Image &depthMm;
	const Gray8Image &alpha;
	const RgbImage &composite;
};

// Writes colour.png, depth.png (false colour, near = red), alpha.png and
// composite.png into dir (created if missing). Empty images are skipped.
// Returns 0 or a negative errno with error naming the file.
int writeSnapshotImages(const std::string &dir, const SnapshotImages &images, std::string &error);

} // namespace depthkey
