// `make run`'s config (daemon/run-sim.sh): the shipped config/depthkey.toml
// with only [mapping] calibration_file changed, to the calibration `make`
// fits to the simulator, and that calibration loads and fits the simulated
// cameras. The shipped file itself stays uncalibrated.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

#include "config/board_calibration_file.hpp"
#include "config/calibration_file.hpp"
#include "hal/sim/board_display.hpp"
#include "config/config_loader.hpp"
#include "hal/sim/lecture_simulator.hpp"
#include "tests/process/shell_command.hpp"
#include "tests/test_paths.hpp"

namespace depthkey {
namespace {

const std::string kEmptyCalibrationLine = "calibration_file = \"\"";

std::string readFile(const std::string &path)
{
	std::ifstream in(path);
	std::stringstream text;
	text << in.rdbuf();
	return text.str();
}

// "line N: ACTUAL instead of EXPECTED" for the first line that differs, "" when none does.
std::string firstDifference(const std::string &actual, const std::string &expected)
{
	std::istringstream a(actual), e(expected);
	std::string lineA, lineE;
	for (int n = 1;; n++) {
		bool moreA = static_cast<bool>(std::getline(a, lineA));
		bool moreE = static_cast<bool>(std::getline(e, lineE));
		if (!moreA && !moreE)
			return "";
		if (moreA != moreE || lineA != lineE)
			return "line " + std::to_string(n) + ": " + (moreA ? lineA : "(end)") + " instead of " +
			       (moreE ? lineE : "(end)");
	}
}

// build/ (or build/san/): the Makefile's BUILD, where make run keeps its files.
std::string buildDir()
{
	std::string bin = test::binDir();
	return bin.substr(0, bin.rfind('/'));
}

// RUN_SIM_PREPARE_ONLY=1 run-sim.sh BIN BUILD [CONFIG], from the source tree.
std::string prepare(const std::string &build, const std::string &config, int &status)
{
	return test::run("cd '" + test::sourceDir() + "' && RUN_SIM_PREPARE_ONLY=1 sh daemon/run-sim.sh '" +
				 test::binDir() + "' '" + build + "' " + config,
			 status);
}

TEST(RunSimConfig, ShippedConfigPointedAtTheSimCalibration)
{
	std::string build = buildDir();
	std::string calibration = build + "/sim-calibration.toml";
	int status = 0;
	// make run makes it; a test binary built with `make check` alone makes it the same way.
	if (access(calibration.c_str(), R_OK) != 0) {
		std::string out = test::run(test::binDir() + "/depthkey-calibrate --sim --output " + calibration, status);
		ASSERT_EQ(status, 0) << out;
	}
	std::string board = build + "/sim-board.toml";
	if (access(board.c_str(), R_OK) != 0) {
		std::string out = test::run(test::binDir() + "/depthkey-calibrate --board --sim --output " + board, status);
		ASSERT_EQ(status, 0) << out;
	}

	std::string out = prepare(build, "", status);
	ASSERT_EQ(status, 0) << out;
	std::string config = test::lastLine(out);
	EXPECT_EQ(config, build + "/run.toml");

	// Word for word the shipped file but for the two lines.
	std::string shipped = readFile(test::sourceDir() + "/config/depthkey.toml");
	size_t line = shipped.find(kEmptyCalibrationLine);
	ASSERT_NE(line, std::string::npos) << "config/depthkey.toml must ship uncalibrated";
	std::string expected = shipped;
	expected.replace(line, kEmptyCalibrationLine.size(), "calibration_file = \"" + calibration + "\"");
	const std::string emptyBoardLine = "homography_file = \"\"";
	size_t boardLine = expected.find(emptyBoardLine);
	ASSERT_NE(boardLine, std::string::npos) << "config/depthkey.toml must ship without a board calibration";
	expected.replace(boardLine, emptyBoardLine.size(), "homography_file = \"" + board + "\"");
	EXPECT_EQ(firstDifference(readFile(config), expected), "");

	ConfigResult loaded = loadConfig(config);
	for (const ConfigError &e : loaded.errors)
		ADD_FAILURE() << e.toString();
	ASSERT_TRUE(loaded.ok());
	const Settings &settings = loaded.settings;
	EXPECT_EQ(settings.mapping.calibrationFile, calibration);
	EXPECT_EQ(settings.colour.backend, "sim");
	EXPECT_EQ(settings.depth.backend, "sim");
	// The board calibration fits the simulated board make run shows.
	EXPECT_EQ(settings.board.backend, "sim");
	BoardCalibrationResult boardResult = loadBoardCalibration(settings.board.homographyFile);
	ASSERT_TRUE(boardResult.ok()) << boardResult.errors.front().toString();
	EXPECT_EQ(boardResult.calibration.colourWidth, settings.colour.width);
	EXPECT_EQ(boardResult.calibration.boardWidth, settings.board.width);
	EXPECT_EQ(boardResult.calibration.boardHeight, simBoardHeight(settings.board.width));

	CalibrationResult result = loadCalibration(settings.mapping.calibrationFile);
	for (const ConfigError &e : result.errors)
		ADD_FAILURE() << e.toString();
	ASSERT_TRUE(result.ok());
	const MappingModel &mapping = result.calibration.mapping;
	EXPECT_EQ(mapping.colourWidth, settings.colour.width);
	EXPECT_EQ(mapping.colourHeight, settings.colour.height);
	EXPECT_EQ(mapping.tofWidth, LectureSimulator::kTofWidth);
	EXPECT_EQ(mapping.tofHeight, LectureSimulator::kTofHeight);
	EXPECT_EQ(result.calibration.colourCamera, "sim colour 640x480 seed " + std::to_string(settings.sim.seed));
}

class RunSimConfigErrors : public ::testing::Test
{
protected:
	void SetUp() override
	{
		char templ[] = "/tmp/depthkey-run-sim-XXXXXX";
		ASSERT_NE(mkdtemp(templ), nullptr);
		dir_ = templ;
	}
	void TearDown() override { std::filesystem::remove_all(dir_); }

	void write(const std::string &name, const std::string &text) { std::ofstream(dir_ + "/" + name) << text; }

	std::string dir_;
};

TEST_F(RunSimConfigErrors, ConfigWithoutAnEmptyCalibrationLineIsRefused)
{
	write("sim-calibration.toml", "");
	write("custom.toml", "[mapping]\ncalibration_file = \"/var/lib/depthkey/calibration.toml\"\n");
	int status = 0;
	std::string out = prepare(dir_, dir_ + "/custom.toml", status);
	EXPECT_EQ(status, 1) << out;
	EXPECT_NE(out.find(dir_ + "/custom.toml: expected exactly one line 'calibration_file = \"\"'"),
		  std::string::npos)
		<< out;
	EXPECT_FALSE(std::filesystem::exists(dir_ + "/run.toml"));
}

TEST_F(RunSimConfigErrors, MissingCalibrationSaysHowToMakeIt)
{
	int status = 0;
	std::string out = prepare(dir_, "", status);
	EXPECT_EQ(status, 1) << out;
	EXPECT_NE(out.find(dir_ + "/sim-calibration.toml is missing: make run fits it"), std::string::npos) << out;
	EXPECT_FALSE(std::filesystem::exists(dir_ + "/run.toml"));
}

TEST_F(RunSimConfigErrors, MissingBoardCalibrationSaysHowToMakeIt)
{
	write("sim-calibration.toml", "");
	int status = 0;
	std::string out = prepare(dir_, "", status);
	EXPECT_EQ(status, 1) << out;
	EXPECT_NE(out.find(dir_ + "/sim-board.toml is missing: make run fits it"), std::string::npos) << out;
	EXPECT_NE(out.find("depthkey-calibrate --board --sim --output"), std::string::npos) << out;
	EXPECT_FALSE(std::filesystem::exists(dir_ + "/run.toml"));
}

// Issue 30: the banner names the preview page and signals this daemon by its
// own PID. A stand-in depthkeyd (the script execs it, so it has the
// script's PID) prints its PID, which the banner's kill lines must name.
TEST_F(RunSimConfigErrors, BannerNamesThePreviewAndThisDaemonsPid)
{
	write("sim-calibration.toml", "");
	write("sim-board.toml", "");
	std::filesystem::create_directories(dir_ + "/bin");
	write("bin/depthkeyd", "#!/bin/sh\necho \"stand-in pid $$\"\n");
	std::filesystem::permissions(dir_ + "/bin/depthkeyd", std::filesystem::perms::owner_all);
	int status = 0;
	std::string out = test::run("cd '" + test::sourceDir() + "' && sh daemon/run-sim.sh '" + dir_ + "/bin' '" + dir_ + "'",
				    status);
	ASSERT_EQ(status, 0) << out;
	size_t at = out.find("stand-in pid ");
	ASSERT_NE(at, std::string::npos) << out;
	std::string pid = out.substr(at + 13, out.find('\n', at) - at - 13);
	EXPECT_NE(out.find("the preview page: http://127.0.0.1:8080/"), std::string::npos) << out;
	EXPECT_NE(out.find("  kill -USR1 " + pid + " "), std::string::npos) << out;
	EXPECT_NE(out.find("  kill -HUP " + pid + " "), std::string::npos) << out;
	EXPECT_EQ(out.find("pidof"), std::string::npos) << out;
}

} // namespace
} // namespace depthkey
