#include "daemon/setup_tracker.hpp"

namespace depthkey {

const PreviewSetup &SetupTracker::update(const Settings &settings, const CalibrationFacts &facts)
{
	if (stale_ || !facts_ || !(*facts_ == facts)) {
		setup_ = setupReport(settings, configPath_, facts);
		facts_ = facts;
		stale_ = false;
	}
	return setup_;
}

std::optional<PreviewSetupDevice> SetupTracker::missing(const Settings &settings, const CalibrationFacts &facts,
							const std::string &role)
{
	stale_ = true;
	for (const PreviewSetupDevice &d : update(settings, facts).devices)
		if (d.role == role && !d.found)
			return d;
	return std::nullopt;
}

} // namespace depthkey
