#include "daemon/setup_report.hpp"

#include "config/board_calibration_file.hpp"
#include "config/calibration_file.hpp"

namespace depthkey {

namespace {

std::string camera(const std::string &backend, const std::string &device, const char *onABox)
{
	if (backend == "sim")
		return std::string("simulated (backend \"sim\"; a box names ") + onABox + " here)";
	if (backend == "replay")
		return "a recorded sequence (backend \"replay\")";
	if (backend == "sr2")
		return "SwissRanger SR-2 over USB (backend \"sr2\")";
	return backend + " " + device;
}

template<typename Result>
std::string fileState(const std::string &path, const Result &result)
{
	if (result.ok())
		return "calibrated (" + path + ")";
	return "NOT calibrated: " + path + " is refused (" + result.errors.front().toString() + ")";
}

} // namespace

std::string describeSetup(const Settings &s)
{
	std::string out;
	out += "colour camera: " + camera(s.colour.backend, s.colour.device, "\"v4l2\"") + "\n";
	out += "depth camera: " + camera(s.depth.backend, s.depth.device, "\"sr2\" or \"v4l2\"") + "\n";
	out += "depth calibration: " +
	       (s.mapping.calibrationFile.empty()
			? std::string("NOT calibrated (mapping.calibration_file is empty): depthkey-calibrate --live "
				      "--output /var/lib/depthkey/calibration.toml, then set the key")
			: fileState(s.mapping.calibrationFile, loadCalibration(s.mapping.calibrationFile))) +
	       "\n";
	out += "board: backend \"" + s.board.backend + "\"; geometry " +
	       (s.board.homographyFile.empty()
			? std::string("NOT calibrated (board.homography_file is empty): depthkey-calibrate --board "
				      "--image COLOUR.png --output /var/lib/depthkey/board.toml, then set the key")
			: fileState(s.board.homographyFile, loadBoardCalibration(s.board.homographyFile))) +
	       "\n";
	return out;
}

} // namespace depthkey
