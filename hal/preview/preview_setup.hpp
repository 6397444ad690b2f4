// The box's setup state as the first-run path walks it (issue 30,
// docs/first-run.md): the cameras the config names and whether they answer,
// the depth and the board calibrated or not, and the next command. The
// daemon fills it (daemon/setup_report.hpp); status.json carries it as
// "setup", the preview page shows it, and depthkeyd --check-config prints it.
#pragma once

#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

namespace depthkey {

struct PreviewSetupDevice {
	std::string role;    // "colour camera", "depth camera", "board"
	std::string backend; // the config's: "v4l2", "sr2", "sim", "colour", ...
	std::string device;  // what the config names: a path, "USB 0852:0071", ""
	bool found = false;  // it answered (a simulated one always does)
	std::string name;    // what answered: the V4L2 card, "SwissRanger SR-2 at USB 1-2", ...
	std::string next;    // when not found: what to do; "" otherwise
};

struct PreviewSetupCalibration {
	bool calibrated = false;
	std::string file;  // the calibration file named, "" = none
	std::string state; // in words: "calibrated (FILE)", "NOT calibrated: ..."
	std::string next;  // when not calibrated: the command to run; "" otherwise
};

struct PreviewSetup {
	std::vector<PreviewSetupDevice> devices; // colour camera, depth camera, board
	PreviewSetupCalibration depth, board;
	// The first step still to take, in the order of docs/first-run.md
	// (cameras, then depth calibration, then board); "" when none is left.
	std::string next;
};

// status.json's "setup" object.
nlohmann::json previewSetupJson(const PreviewSetup &setup);

} // namespace depthkey
