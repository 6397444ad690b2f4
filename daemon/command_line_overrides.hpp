// Command-line options that win over the config file, on start and reload.
#pragma once

#include "settings/settings.hpp"

#include <string>

namespace depthkey {

struct CommandLineOverrides {
	std::string snapshotDir;
	std::string recordDir;   // --record DIR
	std::string previewDir;  // --preview DIR: stage images of a few frames (not a setting)
	void applyTo(Settings &settings) const
	{
		if (!snapshotDir.empty())
			settings.daemon.snapshotDir = snapshotDir;
		if (!recordDir.empty())
			settings.daemon.recordDir = recordDir;
	}
};

} // namespace depthkey
