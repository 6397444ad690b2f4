// depthkey-calibrate --live end to end on the simulated cameras: the tool
// opens the cameras of a config as depthkeyd does, a simulated technician
// (hal/sim/sim_technician.hpp) carries the pattern where the tool says, the
// tool takes each view once both cameras have seen the whole grid still for
// 0.5 s, fits and writes the file. Run as a process with a time limit. The
// room is the simulator's with the desk moved aside (it would hide the
// pattern at 1.6 m on the right), and the plan stops at 1.6 m: the board
// stands at 2 m, and a pattern cannot be held behind it.
#include <gtest/gtest.h>

#include "config/calibration_file.hpp"
#include "hal/sim/lecture_simulator.hpp"
#include "tests/process/shell_command.hpp"
#include "tests/test_paths.hpp"

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <string>

using namespace depthkey;

namespace {

class CalibrateLive : public ::testing::Test
{
protected:
	void SetUp() override
	{
		char templ[] = "/tmp/depthkey-calibrate-live-XXXXXX";
		dir_ = mkdtemp(templ);
	}
	void TearDown() override { (void)std::system(("rm -rf '" + dir_ + "'").c_str()); }
	std::string config(const std::string &text)
	{
		std::string path = dir_ + "/depthkey.toml";
		std::ofstream(path) << text;
		return path;
	}
	std::string dir_;
};

int count(const std::string &text, const std::string &word)
{
	int n = 0;
	for (size_t at = text.find(word); at != std::string::npos; at = text.find(word, at + 1))
		n++;
	return n;
}

} // namespace

TEST_F(CalibrateLive, SimulatedCamerasGiveACalibrationCloseToTheTruth)
{
	const std::string cfg = config("[sim]\ntable = false\n");
	const auto start = std::chrono::steady_clock::now();
	int status = -1;
	// The time limit: 15 views of about 1.5 s each, with room for a loaded machine.
	// The default depths: the room's board stands 2 m away, so the tool
	// leaves out the 2.0 and 2.5 m views (they could only time out).
	const std::string out = test::run("timeout 180 " + test::binDir() + "/depthkey-calibrate --live --config " +
					  cfg + " --view-timeout 20 --output " + dir_ + "/live.toml",
				  status);
	const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
	std::printf("[ live     ] %.1f s for 15 views\n", seconds);
	ASSERT_EQ(status, 0) << out;
	// The views' instructions, not a reason why one is not seen yet ("hold
	// the pattern upright", said 1.5 s into a slow view).
	EXPECT_NE(out.find("the views at 2.0, 2.5 m would be behind it or against it, left out"), std::string::npos) << out;
	EXPECT_EQ(count(out, "/15: hold the pattern"), 15) << out;
	EXPECT_NE(out.find("view  2/15: hold the pattern 0.9 m from the camera, top left of the image"),
		  std::string::npos)
		<< out;
	EXPECT_EQ(count(out, "accepted: 35 circles"), 15) << out;
	EXPECT_EQ(out.find("rejected"), std::string::npos) << out;
	// Each view waits for the pattern carried there (0.8 s) and held still 0.5 s.
	EXPECT_GT(seconds, 15 * 1.3);
	EXPECT_NE(test::lastLine(out).find("summary model=parallax"), std::string::npos) << out;

	CalibrationResult loaded = loadCalibration(dir_ + "/live.toml");
	for (const ConfigError &e : loaded.errors)
		ADD_FAILURE() << e.toString();
	ASSERT_TRUE(loaded.ok());
	EXPECT_EQ(loaded.calibration.depthsM, (std::vector<double>{ 0.9, 1.2, 1.6 }));
	EXPECT_EQ(loaded.calibration.colourCamera, "sim-colour seed 1 640x480");

	// Against the simulator's own camera pair over the depths calibrated.
	LectureSimulator scene;
	SimSettings sim;
	sim.table = false;
	scene.configure(sim, 640, 480);
	const CameraRig &rig = scene.rig();
	double sumSquares = 0;
	int points = 0;
	for (double z = 0.9; z <= 1.601; z += 0.1)
		for (int v = 0; v < rig.tof().height; v += 2)
			for (int u = 0; u < rig.tof().width; u += 2) {
				double tx, ty, x, y;
				if (!rig.tofToColour(u, v, z, tx, ty) || tx < 0 || ty < 0 || tx > 639 || ty > 479)
					continue;
				loaded.calibration.mapping.map(u, v, z, x, y);
				sumSquares += (x - tx) * (x - tx) + (y - ty) * (y - ty);
				points++;
			}
	const double rms = std::sqrt(sumSquares / points);
	std::printf("[ live     ] error against the truth at 0.9-1.6 m: %.3f px RMS over %d points\n", rms, points);
	EXPECT_LE(rms, 0.5);
}

TEST_F(CalibrateLive, ACameraThatCannotBeOpenedIsNamedAndTheFileLeftAlone)
{
	const std::string cfg = config("[colour]\nbackend = \"v4l2\"\ndevice = \"/nonexistent/video0\"\n");
	std::ofstream(dir_ + "/good.toml") << "keep";
	int status = -1;
	const std::string out = test::run("timeout 60 " + test::binDir() + "/depthkey-calibrate --live --config " +
					  cfg + " --depths 0.9 --view-timeout 1 --output " + dir_ + "/good.toml",
				  status);
	EXPECT_EQ(status, 1) << out;
	EXPECT_NE(out.find("colour camera v4l2-colour lost: /nonexistent/video0"), std::string::npos) << out;
	EXPECT_NE(out.find("is depthkeyd running?"), std::string::npos) << out;
	// Without frames there is no view to judge: it stops at the first.
	EXPECT_NE(out.find("no frame from the colour camera in 1 s"), std::string::npos) << out;
	EXPECT_EQ(count(out, "hold the pattern"), 1) << out;
	std::ifstream kept(dir_ + "/good.toml");
	std::string text((std::istreambuf_iterator<char>(kept)), std::istreambuf_iterator<char>());
	EXPECT_EQ(text, "keep");
}

TEST(CalibrateLiveOptions, ConfigWithoutLiveIsAUsageError)
{
	int status = -1;
	const std::string out = test::run(test::binDir() + "/depthkey-calibrate --sim --config /etc/x.toml --output /tmp/x",
					  status);
	EXPECT_EQ(status, 2) << out;
	EXPECT_NE(out.find("--live [--config FILE]"), std::string::npos) << out;
}

// make run's room, desk included (issue 30): at 1.6 m on the right the desk
// hides part of the pattern. The tool says so within 2 s of the instruction,
// naming the camera and the circles it found, not only at the timeout.
TEST_F(CalibrateLive, AHiddenGridIsExplainedWithinTwoSeconds)
{
	const std::string cfg = config("[sim]\n");
	int status = -1;
	const std::string out = test::run("timeout 120 " + test::binDir() + "/depthkey-calibrate --live --config " + cfg +
						  " --depths 1.6 --view-timeout 4 --output " + dir_ + "/live.toml",
					  status);
	size_t view3 = out.find("view  3/5: hold the pattern 1.6 m from the camera, top right of the image");
	ASSERT_NE(view3, std::string::npos) << out;
	size_t line = out.find("        colour camera, ", view3);
	ASSERT_NE(line, std::string::npos) << out;
	double seconds = 0;
	int found = 0;
	ASSERT_EQ(std::sscanf(out.c_str() + line, " colour camera, %lf s into the view: %d of 35 circles found", &seconds,
			      &found),
		  2)
		<< out;
	EXPECT_LE(seconds, 2.0) << out;
	EXPECT_GT(found, 0) << out;
	EXPECT_LT(found, 35) << out;
	EXPECT_NE(out.find("the rest are hidden (by the desk, a monitor, a hand?)", line), std::string::npos) << out;
	EXPECT_NE(out.find("rejected: neither camera sees the whole 7x5 grid: colour: ", line), std::string::npos) << out;
}
