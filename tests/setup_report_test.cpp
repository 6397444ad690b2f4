// depthkeyd --check-config's setup state (issue 30): cameras named, depth
// and board calibration said calibrated or not, with the next command.
#include "daemon/setup_report.hpp"

#include <gtest/gtest.h>

namespace depthkey {
namespace {

TEST(SetupReport, TheShippedDefaultsSayNotCalibratedAndWhatToRun)
{
	Settings s;
	std::string text = describeSetup(s);
	EXPECT_NE(text.find("colour camera: simulated"), std::string::npos) << text;
	EXPECT_NE(text.find("depth calibration: NOT calibrated (mapping.calibration_file is empty): depthkey-calibrate --live"),
		  std::string::npos)
		<< text;
	EXPECT_NE(text.find("geometry NOT calibrated (board.homography_file is empty): depthkey-calibrate --board"),
		  std::string::npos)
		<< text;
}

TEST(SetupReport, RealCamerasAndABadCalibrationFileAreNamed)
{
	Settings s;
	s.colour.backend = "v4l2";
	s.colour.device = "/dev/v4l/by-id/usb-cam-video-index0";
	s.depth.backend = "sr2";
	s.mapping.calibrationFile = "/nonexistent/calibration.toml";
	std::string text = describeSetup(s);
	EXPECT_NE(text.find("colour camera: v4l2 /dev/v4l/by-id/usb-cam-video-index0\n"), std::string::npos) << text;
	EXPECT_NE(text.find("depth camera: SwissRanger SR-2 over USB"), std::string::npos) << text;
	EXPECT_NE(text.find("depth calibration: NOT calibrated: /nonexistent/calibration.toml is refused ("),
		  std::string::npos)
		<< text;
}

} // namespace
} // namespace depthkey
