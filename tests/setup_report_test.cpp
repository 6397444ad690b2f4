// depthkeyd --check-config's setup state, status.json's "setup" and the
// journal's line per missing device (issue 30): cameras named and looked
// for, depth and board said calibrated or not, with the next command.
#include "daemon/setup_report.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace depthkey {
namespace {

TEST(SetupReport, TheShippedDefaultsSayNotCalibratedAndWhatToRun)
{
	Settings s;
	PreviewSetup setup = setupReport(s, "config/depthkey.toml", calibrationFromFiles(s));
	std::string text = describeSetup(setup);
	EXPECT_NE(text.find("colour camera: sim, found: simulated"), std::string::npos) << text;
	EXPECT_NE(text.find("depth calibration: NOT calibrated (mapping.calibration_file is empty): print the pattern "
			    "(`depthkey-calibrate --print-pattern pattern.pdf`)"),
		  std::string::npos)
		<< text;
	EXPECT_NE(text.find("board calibration: NOT calibrated (board.homography_file is empty): "
			    "`depthkey-calibrate --board --image"),
		  std::string::npos)
		<< text;
	// The simulated cameras are there: the next step is the depth calibration.
	EXPECT_EQ(setup.next.rfind("depth calibration: print the pattern", 0), 0u) << setup.next;
}

TEST(SetupReport, AMissingCameraIsTheNextStepWithItsPathAndTheCheckCommand)
{
	Settings s;
	s.colour.backend = "v4l2";
	s.colour.device = "/nonexistent/video0";
	s.depth.backend = "sr2";
	s.depth.usbPath = "9-9.9"; // no such port on any machine the tests run on
	s.board.backend = "colour";
	s.mapping.calibrationFile = "/nonexistent/calibration.toml";
	PreviewSetup setup = setupReport(s, "/etc/depthkey/depthkey.toml", calibrationFromFiles(s));
	ASSERT_EQ(setup.devices.size(), 3u);
	EXPECT_FALSE(setup.devices[0].found);
	EXPECT_EQ(missingDeviceLine(setup.devices[0]),
		  "colour camera /nonexistent/video0 not found: plug it in, then "
		  "`sudo depthkeyd --check-config /etc/depthkey/depthkey.toml`");
	EXPECT_FALSE(setup.devices[1].found);
	EXPECT_EQ(missingDeviceLine(setup.devices[1]),
		  "depth camera SR-2 (USB 0852:0071 at 9-9.9) not found: plug it in and switch on its power "
		  "supply, then `sudo depthkeyd --check-config /etc/depthkey/depthkey.toml`");
	EXPECT_TRUE(setup.devices[2].found);
	EXPECT_EQ(setup.devices[2].name, "a solid #1e3c28 (docs/board.md connects the board)");
	EXPECT_EQ(setup.next, "colour camera /nonexistent/video0: plug it in, then "
			      "`sudo depthkeyd --check-config /etc/depthkey/depthkey.toml`");
	EXPECT_NE(setup.depth.state.find("NOT calibrated: /nonexistent/calibration.toml is refused ("), std::string::npos)
		<< setup.depth.state;
}

TEST(SetupReport, CalibratedEverywhereLeavesNoNextStep)
{
	Settings s;
	CalibrationFacts facts{ true, "calibrated (a.toml)", true, "calibrated (b.toml)" };
	PreviewSetup setup = setupReport(s, "x.toml", facts);
	EXPECT_EQ(setup.next, "");
	EXPECT_EQ(setup.depth.next, "");
	EXPECT_EQ(setup.board.next, "");
	EXPECT_NE(describeSetup(setup).find("next: nothing; record (docs/first-run.md)"), std::string::npos);
}

TEST(SetupReport, StatusJsonCarriesTheSameReport)
{
	Settings s;
	s.colour.backend = "v4l2";
	s.colour.device = "/nonexistent/video0";
	PreviewSetup setup = setupReport(s, "c.toml", calibrationFromFiles(s));
	nlohmann::json j = previewSetupJson(setup);
	EXPECT_EQ(j["ready"], false);
	EXPECT_EQ(j["next"], setup.next);
	ASSERT_EQ(j["devices"].size(), 3u);
	EXPECT_EQ(j["devices"][0]["role"], "colour camera");
	EXPECT_EQ(j["devices"][0]["device"], "/nonexistent/video0");
	EXPECT_EQ(j["devices"][0]["found"], false);
	EXPECT_EQ(j["devices"][1]["found"], true); // the simulated depth camera
	EXPECT_EQ(j["depth_calibration"]["calibrated"], false);
	EXPECT_EQ(j["board_calibration"]["next"], setup.board.next);
}

} // namespace
} // namespace depthkey
