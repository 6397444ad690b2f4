// depthkey-calibrate --board end to end: the pattern file, the summary line,
// the written file, the refusal limit, bad use. The fit itself is
// tests/board_calibration_test.cpp's.
#include "algo/board_calibration.hpp"
#include "config/board_calibration_file.hpp"
#include "hal/image_file.hpp"
#include "hal/sim/board_display.hpp"
#include "tests/process/shell_command.hpp"
#include "tests/test_paths.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <unistd.h>

using namespace depthkey;

namespace {

std::string tempDir(const char *name)
{
	auto dir = std::filesystem::temp_directory_path() / (std::string("depthkey-") + name + "-" + std::to_string(getpid()));
	std::filesystem::remove_all(dir);
	std::filesystem::create_directories(dir);
	return dir.string();
}

} // namespace

TEST(BoardCalibrateTool, SimWritesTheFileAndEndsWithTheSummary)
{
	std::string dir = tempDir("board-cal");
	int status;
	std::string out = test::run(test::binDir() + "/depthkey-calibrate --board --sim --no-distortion --output " +
					    dir + "/board.toml --write-board-pattern " + dir + "/pattern.png",
				    status);
	ASSERT_EQ(status, 0) << out;
	double rms = -1, max = -1;
	ASSERT_EQ(std::sscanf(test::lastLine(out).c_str(), "summary board rms_px=%lf max_px=%lf", &rms, &max), 2) << out;
	EXPECT_LT(rms, 0.5);
	EXPECT_GE(max, rms);
	double truthRms = -1;
	size_t at = out.find("against the simulator's truth");
	ASSERT_NE(at, std::string::npos) << out;
	ASSERT_EQ(std::sscanf(out.c_str() + out.find("rms ", at), "rms %lf", &truthRms), 1);
	EXPECT_LT(truthRms, 0.5);

	BoardCalibrationResult loaded = loadBoardCalibration(dir + "/board.toml");
	ASSERT_TRUE(loaded.ok()) << loaded.errors.front().toString();
	EXPECT_EQ(loaded.calibration.boardWidth, 1920);
	EXPECT_EQ(loaded.calibration.boardHeight, simBoardHeight(1920));
	EXPECT_EQ(loaded.calibration.colourWidth, 640);

	// The pattern file is the board's resolution and has the circles.
	RgbImage pattern;
	std::string error;
	ASSERT_EQ(readRgbImage(dir + "/pattern.png", pattern, error), 0) << error;
	EXPECT_EQ(pattern.width(), 1920);
	BoardPattern layout{ 1920, simBoardHeight(1920) };
	ImagePoint c = layout.centre(0);
	EXPECT_LT(pattern.at(int(c.x), int(c.y)).r, 20);
	EXPECT_GT(pattern.at(int(c.x + layout.spacingPx() / 2), int(c.y)).r, 235);

	// The simulator's default, its lens distorting: the written file holds
	// the lens, and the truth is still within 0.5 board px.
	out = test::run(test::binDir() + "/depthkey-calibrate --board --sim --output " + dir + "/board-lens.toml", status);
	ASSERT_EQ(status, 0) << out;
	at = out.find("against the simulator's truth");
	ASSERT_NE(at, std::string::npos) << out;
	ASSERT_EQ(std::sscanf(out.c_str() + out.find("rms ", at), "rms %lf", &truthRms), 1);
	EXPECT_LT(truthRms, 0.5) << out;
	BoardCalibrationResult withLens = loadBoardCalibration(dir + "/board-lens.toml");
	ASSERT_TRUE(withLens.ok()) << withLens.errors.front().toString();
	EXPECT_LT(withLens.calibration.lensK1, -0.02);
	EXPECT_NE(out.find("colour lens: k1 -0.0"), std::string::npos) << out;

	// Over the limit: refused, the file left as it was, the summary still last.
	std::string before = formatBoardCalibration(loaded.calibration);
	out = test::run(test::binDir() + "/depthkey-calibrate --board --sim --max-rms 0.0001 --output " + dir +
				"/board.toml",
			status);
	EXPECT_EQ(status, 1) << out;
	EXPECT_NE(out.find("refused: rms"), std::string::npos) << out;
	EXPECT_EQ(test::lastLine(out).rfind("summary board rms_px=", 0), 0u) << out;
	BoardCalibrationResult after = loadBoardCalibration(dir + "/board.toml");
	ASSERT_TRUE(after.ok());
	EXPECT_EQ(formatBoardCalibration(after.calibration), before);
	std::filesystem::remove_all(dir);
}

TEST(BoardCalibrateTool, BadUseIsAUsageError)
{
	int status;
	std::string out = test::run(test::binDir() + "/depthkey-calibrate --board", status);
	EXPECT_EQ(status, 2) << out;
	EXPECT_NE(out.find("--board needs"), std::string::npos) << out;
	out = test::run(test::binDir() + "/depthkey-calibrate --board --sim --board-size 12x9000", status);
	EXPECT_EQ(status, 2) << out;
	out = test::run(test::binDir() + "/depthkey-calibrate --board --image /nonexistent/colour.png", status);
	EXPECT_EQ(status, 1) << out;
	EXPECT_NE(out.find("/nonexistent/colour.png"), std::string::npos) << out;
}
