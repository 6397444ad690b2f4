#include "daemon/setup_report.hpp"

#include "config/board_calibration_file.hpp"
#include "config/calibration_file.hpp"
#include "hal/sr2/sr2_usb_device.hpp"
#include "hal/v4l2/v4l2_stream.hpp"
#include "hal/v4l2/v4l2_video_device.hpp"

#include <cstdio>
#include <cstring>
#include <unistd.h>

namespace depthkey {

namespace {

std::string checkCommand(const std::string &configPath)
{
	// The packaged config is root's to read, and depthkeyd is in /usr/sbin.
	bool system = configPath.rfind("/etc/", 0) == 0;
	return std::string("`") + (system ? "sudo " : "") + "depthkeyd --check-config " + configPath + "`";
}

PreviewSetupDevice videoDevice(const char *role, const std::string &backend, const std::string &configured,
			       const std::string &configPath)
{
	PreviewSetupDevice d{ role, backend, resolveVideoDevice(configured), false, "", "" };
	V4l2VideoDevice probe;
	int ret = probe.open(d.device);
	d.found = ret >= 0;
	if (d.found)
		d.name = probe.card();
	else if (ret == -ENOENT || ret == -ENODEV || ret == -ENXIO)
		d.next = "plug it in, then " + checkCommand(configPath);
	else
		d.next = std::string(std::strerror(-ret)) + ": check `ls -l " + d.device +
			 "` (the daemon's user is in group video), then " + checkCommand(configPath);
	return d;
}

PreviewSetupDevice sr2Device(const std::string &usbPath, const std::string &configPath)
{
	PreviewSetupDevice d{ "depth camera", "sr2", "SR-2 (USB 0852:0071" + (usbPath.empty() ? "" : " at " + usbPath) + ")",
			      false, "", "" };
	std::string port = findSr2(usbPath);
	d.found = !port.empty();
	if (d.found)
		d.name = "SwissRanger SR-2 at USB " + port;
	else
		d.next = "plug it in and switch on its power supply, then " + checkCommand(configPath);
	return d;
}

PreviewSetupDevice simulated(const char *role, const char *onABox)
{
	return { role, "sim", "", true, std::string("simulated (a box names ") + onABox + " in the config)", "" };
}

PreviewSetupDevice replayed(const char *role, const Settings &s)
{
	return { role, "replay", s.replay.path, true, "a recorded sequence", "" };
}

PreviewSetupDevice colourCamera(const Settings &s, const std::string &configPath)
{
	if (s.colour.backend == "v4l2")
		return videoDevice("colour camera", "v4l2", s.colour.device, configPath);
	if (s.colour.backend == "replay")
		return replayed("colour camera", s);
	return simulated("colour camera", "backend \"v4l2\"");
}

PreviewSetupDevice depthCamera(const Settings &s, const std::string &configPath)
{
	if (s.depth.backend == "sr2")
		return sr2Device(s.depth.usbPath, configPath);
	if (s.depth.backend == "v4l2")
		return videoDevice("depth camera", "v4l2", s.depth.device, configPath);
	if (s.depth.backend == "replay")
		return replayed("depth camera", s);
	return simulated("depth camera", "backend \"sr2\" or \"v4l2\"");
}

PreviewSetupDevice board(const Settings &s, const std::string &configPath)
{
	if (s.board.backend == "v4l2")
		return videoDevice("board", "v4l2", s.board.device, configPath);
	if (s.board.backend == "image") {
		bool readable = access(s.board.image.c_str(), R_OK) == 0;
		return { "board", "image", s.board.image, readable, readable ? "picture file" : "",
			 readable ? "" : "the board's computer writes it; until then the board shows board.colour" };
	}
	if (s.board.backend == "colour") {
		char colour[16];
		std::snprintf(colour, sizeof(colour), "#%06x", s.board.colour & 0xffffffu);
		return { "board", "colour", "", true, std::string("a solid ") + colour + " (docs/board.md connects the board)",
			 "" };
	}
	return simulated("board", "backend \"colour\", \"image\" or \"v4l2\"");
}

template<typename Result>
std::string fileState(const std::string &path, const Result &result)
{
	if (result.ok())
		return "calibrated (" + path + ")";
	return "NOT calibrated: " + path + " is refused (" + result.errors.front().toString() + ")";
}

} // namespace

CalibrationFacts calibrationFromFiles(const Settings &s)
{
	CalibrationFacts f;
	if (s.mapping.calibrationFile.empty()) {
		f.depthState = "NOT calibrated (mapping.calibration_file is empty)";
	} else {
		CalibrationResult result = loadCalibration(s.mapping.calibrationFile);
		f.depth = result.ok();
		f.depthState = fileState(s.mapping.calibrationFile, result);
	}
	if (s.board.homographyFile.empty()) {
		f.boardState = "NOT calibrated (board.homography_file is empty)";
	} else {
		BoardCalibrationResult result = loadBoardCalibration(s.board.homographyFile);
		f.board = result.ok();
		f.boardState = fileState(s.board.homographyFile, result);
	}
	return f;
}

PreviewSetup setupReport(const Settings &s, const std::string &configPath, const CalibrationFacts &facts)
{
	PreviewSetup setup;
	setup.devices = { colourCamera(s, configPath), depthCamera(s, configPath), board(s, configPath) };
	setup.depth = { facts.depth, s.mapping.calibrationFile, facts.depthState, "" };
	if (!facts.depth)
		setup.depth.next = "print the pattern (`depthkey-calibrate --print-pattern pattern.pdf`), stop the "
				   "service, `depthkey-calibrate --live --config " + configPath +
				   " --output /var/lib/depthkey/calibration.toml`, set mapping.calibration_file "
				   "(docs/first-run.md)";
	setup.board = { facts.board, s.board.homographyFile, facts.boardState, "" };
	if (!facts.board)
		setup.board.next = "`depthkey-calibrate --board --image SNAPSHOT_DIR/colour.png --board-size WxH "
				   "--output /var/lib/depthkey/board.toml`, set board.homography_file (docs/first-run.md)";
	for (const PreviewSetupDevice &d : setup.devices)
		if (!d.found && setup.next.empty() && d.role != "board")
			setup.next = d.role + " " + d.device + ": " + d.next;
	if (setup.next.empty())
		setup.next = !setup.depth.next.empty() ? "depth calibration: " + setup.depth.next
							: !setup.board.next.empty() ? "board calibration: " + setup.board.next : "";
	return setup;
}

std::string describeSetup(const PreviewSetup &setup)
{
	std::string out;
	for (const PreviewSetupDevice &d : setup.devices) {
		out += d.role + ": " + d.backend + (d.device.empty() ? "" : " " + d.device);
		out += d.found ? ", found: " + d.name : ", NOT found: " + d.next;
		out += "\n";
	}
	out += "depth calibration: " + setup.depth.state + (setup.depth.next.empty() ? "" : ": " + setup.depth.next) + "\n";
	out += "board calibration: " + setup.board.state + (setup.board.next.empty() ? "" : ": " + setup.board.next) + "\n";
	out += "next: " + (setup.next.empty() ? std::string("nothing; record (docs/first-run.md)") : setup.next) + "\n";
	return out;
}

std::string missingDeviceLine(const PreviewSetupDevice &d)
{
	return d.role + " " + d.device + " not found: " + d.next;
}

} // namespace depthkey
