// The setup report (daemon/setup_report.hpp) as the running daemon keeps it
// for status.json: probed again only when a device changed state, the
// calibration changed or the config was reloaded, not every second (a
// probe opens each V4L2 device the config names).
#pragma once

#include "daemon/setup_report.hpp"

#include <optional>
#include <string>

namespace depthkey {

class SetupTracker
{
public:
	explicit SetupTracker(std::string configPath) : configPath_(std::move(configPath)) {}

	// A device changed state, or the config was reloaded: probe again.
	void invalidate() { stale_ = true; }

	// The report for settings and facts, probed again when stale or when
	// the facts changed since the last one.
	const PreviewSetup &update(const Settings &settings, const CalibrationFacts &facts);

	// The device of a role ("colour camera", "depth camera") when the
	// probe just made does not find it; nothing when it is there.
	std::optional<PreviewSetupDevice> missing(const Settings &settings, const CalibrationFacts &facts,
						  const std::string &role);

private:
	std::string configPath_;
	bool stale_ = true;
	std::optional<CalibrationFacts> facts_;
	PreviewSetup setup_;
};

} // namespace depthkey
