// The box's setup state as the first-run path (issue 30, docs/first-run.md)
// walks it: the cameras the config names and whether they answer (by name),
// the depth and the board calibrated or not, and the next command. One
// report for the three places that say it: depthkeyd --check-config, the
// journal's line per missing device, and status.json / the preview page.
#pragma once

#include "hal/preview/preview_setup.hpp"
#include "settings/settings.hpp"

#include <string>

namespace depthkey {

// Whether the depth and the board are calibrated, in words. The daemon
// knows it from what it runs on; --check-config from the files.
struct CalibrationFacts {
	bool depth = false;
	std::string depthState;
	bool board = false;
	std::string boardState;
	bool operator==(const CalibrationFacts &) const = default;
};

// --check-config's: the calibration files the config names, loaded.
CalibrationFacts calibrationFromFiles(const Settings &settings);

// Looks for each device the config names (a V4L2 device is opened and asked
// its card's name; the SR-2 is looked for on the USB bus, not opened) and
// says what to do next. configPath goes into the commands it names.
PreviewSetup setupReport(const Settings &settings, const std::string &configPath, const CalibrationFacts &facts);

// --check-config's text: "colour camera: ...", "depth camera: ...",
// "board: ...", "depth calibration: ...", "board calibration: ...", "next: ...".
std::string describeSetup(const PreviewSetup &setup);

// The journal's line for a device not found: "colour camera /dev/video0 not
// found: plug it in, then `depthkeyd --check-config FILE`".
std::string missingDeviceLine(const PreviewSetupDevice &device);

} // namespace depthkey
