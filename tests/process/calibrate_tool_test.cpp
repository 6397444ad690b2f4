// depthkey-calibrate end to end on the simulator, whose true depth -> colour
// mapping is known: the written file loads, the parallax model meets the
// accuracy target over the working range, the paper's model is reported as
// it is, and a recorded sequence gives the same calibration.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sys/wait.h>
#include <sstream>

#include "config/calibration_file.hpp"
#include "hal/sim/camera_rig.hpp"
#include "tests/test_paths.hpp"

namespace depthkey {
namespace {

struct ToolRun {
	int status = -1;
	std::string out;        // stdout; stderr is appended after it
	std::string lastLine;
};

ToolRun calibrate(const std::string &args)
{
	ToolRun run;
	std::string command = test::binDir() + "/depthkey-calibrate " + args + " 2>&1";
	FILE *pipe = popen(command.c_str(), "r");
	if (!pipe)
		return run;
	char buf[4096];
	while (size_t n = std::fread(buf, 1, sizeof(buf), pipe))
		run.out.append(buf, n);
	int status = pclose(pipe);
	run.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
	std::string text = run.out;
	while (!text.empty() && text.back() == '\n')
		text.pop_back();
	run.lastLine = text.substr(text.rfind('\n') + 1);
	return run;
}

// The fitted mapping's distance from the truth in colour pixels, at depth z,
// over the whole ToF image (every 2nd pixel) where the truth lands inside the
// colour image: outside it there is nothing to key.
ResidualStats errorAgainstTruth(const MappingModel &model, const CameraRig &rig, double z)
{
	ResidualAccumulator acc;
	for (int v = 0; v < rig.tof().height; v += 2) {
		for (int u = 0; u < rig.tof().width; u += 2) {
			double tx, ty, x, y;
			if (!rig.tofToColour(u, v, z, tx, ty) || tx < -0.5 || ty < -0.5 ||
			    tx > rig.colour().width - 0.5 || ty > rig.colour().height - 0.5)
				continue;
			model.map(u, v, z, x, y);
			acc.add(x - tx, y - ty);
		}
	}
	return acc.stats();
}

struct TruthReport {
	ResidualStats overall;
	std::vector<std::pair<double, ResidualStats>> perDepth;
};

// 0.5 to 2.5 m in steps of 0.25 m: the working range, fitted depths and not.
// The rig depthkey-calibrate --sim uses, at its colour size.
TruthReport compareWithTruth(const MappingModel &model, int colourWidth = 640, int colourHeight = 480)
{
	CameraRig rig;
	rig.configure(colourWidth, colourHeight, true, 60);
	TruthReport report;
	double sumSquares = 0, maxPx = 0;
	int points = 0;
	for (double z = 0.5; z <= 2.501; z += 0.25) {
		ResidualStats s = errorAgainstTruth(model, rig, z);
		report.perDepth.emplace_back(z, s);
		sumSquares += s.rmsPx * s.rmsPx * s.points;
		points += s.points;
		maxPx = std::max(maxPx, s.maxPx);
	}
	report.overall = { points, std::sqrt(sumSquares / points), maxPx };
	return report;
}

void print(const char *name, const TruthReport &report)
{
	std::printf("[ truth    ] %s: error against the simulator's truth, colour px\n", name);
	for (const auto &[z, s] : report.perDepth)
		std::printf("[ truth    ]   z=%.2f m  rms=%.3f  max=%.3f  (%d points)\n", z, s.rmsPx, s.maxPx,
			    s.points);
	std::printf("[ truth    ]   0.5-2.5 m rms=%.3f  max=%.3f\n", report.overall.rmsPx, report.overall.maxPx);
}

class CalibrateTool : public ::testing::Test
{
protected:
	static void SetUpTestSuite()
	{
		char templ[] = "/tmp/depthkey-calibrate-XXXXXX";
		dir_ = mkdtemp(templ);
		sim_ = calibrate("--sim --record " + dir_ + "/seq --output " + dir_ + "/sim.toml");
	}
	static void TearDownTestSuite()
	{
		std::string cmd = "rm -rf '" + dir_ + "'";
		(void)std::system(cmd.c_str());
	}

	static std::string dir_;
	static ToolRun sim_;
};

std::string CalibrateTool::dir_;
ToolRun CalibrateTool::sim_;

// The summary line, parsed and printed back: equal only when it has exactly
// the form scripts expect ("summary model=parallax rms_px=0.31 ...").
bool isSummaryLine(const std::string &line)
{
	char model[16];
	double rms, max, heldout;
	if (std::sscanf(line.c_str(), "summary model=%15s rms_px=%lf max_px=%lf heldout_rms_px=%lf", model,
			&rms, &max, &heldout) != 4)
		return false;
	char again[160];
	std::snprintf(again, sizeof(again), "summary model=%s rms_px=%.2f max_px=%.2f heldout_rms_px=%.2f",
		      model, rms, max, heldout);
	return line == again && (std::string(model) == "paper" || std::string(model) == "parallax");
}

TEST_F(CalibrateTool, SimulatorCalibrationMeetsTheTargetAgainstTheTruth)
{
	ASSERT_EQ(sim_.status, 0) << sim_.out;
	EXPECT_TRUE(isSummaryLine(sim_.lastLine)) << sim_.lastLine;
	EXPECT_NE(sim_.lastLine.find("model=parallax"), std::string::npos) << sim_.out;
	EXPECT_EQ(sim_.out.find("rejected"), std::string::npos) << sim_.out;

	CalibrationResult loaded = loadCalibration(dir_ + "/sim.toml");
	for (const ConfigError &e : loaded.errors)
		ADD_FAILURE() << e.toString();
	ASSERT_TRUE(loaded.ok());
	EXPECT_EQ(loaded.calibration.mapping.kind, MappingKind::Parallax);
	EXPECT_EQ(loaded.calibration.colourCamera, "sim colour 640x480 seed 1");
	EXPECT_EQ(loaded.calibration.depthsM, (std::vector<double>{ 0.9, 1.2, 1.6, 2.0, 2.5 }));

	TruthReport truth = compareWithTruth(loaded.calibration.mapping);
	print("parallax", truth);
	EXPECT_LE(truth.overall.rmsPx, 0.5);
	std::printf("%s", sim_.out.substr(sim_.out.find("residuals in colour pixels")).c_str());
}

TEST_F(CalibrateTool, PaperModelIsReportedAsItIs)
{
	ASSERT_EQ(sim_.status, 0) << sim_.out;
	// From the recorded views: no rendering again.
	ToolRun paper = calibrate("--sequence " + dir_ + "/seq --model paper --max-rms 20 --output " + dir_ +
			      "/paper.toml");
	ASSERT_EQ(paper.status, 0) << paper.out;
	EXPECT_NE(paper.lastLine.find("summary model=paper"), std::string::npos) << paper.lastLine;

	CalibrationResult loaded = loadCalibration(dir_ + "/paper.toml");
	ASSERT_TRUE(loaded.ok());
	EXPECT_EQ(loaded.calibration.selectedBy, "option");
	TruthReport paperTruth = compareWithTruth(loaded.calibration.mapping);
	print("paper", paperTruth);
	TruthReport parallaxTruth = compareWithTruth(loadCalibration(dir_ + "/sim.toml").calibration.mapping);
	// The paper's model has no cross terms and a depth term linear in z: it
	// misses by more than the parallax model everywhere, and most at 0.5 m,
	// below the nearest fitted depth.
	EXPECT_GT(paperTruth.overall.rmsPx, 2 * parallaxTruth.overall.rmsPx);
	EXPECT_GT(paperTruth.perDepth.front().second.rmsPx, paperTruth.overall.rmsPx);
	// Its reported residuals say so too.
	const CalibrationSummary &summary = loaded.calibration.summaries.at(0);
	EXPECT_GT(summary.heldOut.rmsPx, 1.0);
}

TEST_F(CalibrateTool, RecordedSequenceGivesTheSameCalibration)
{
	ASSERT_EQ(sim_.status, 0) << sim_.out;
	ToolRun replay = calibrate("--sequence " + dir_ + "/seq --output " + dir_ + "/seq.toml");
	ASSERT_EQ(replay.status, 0) << replay.out;
	EXPECT_EQ(replay.lastLine, sim_.lastLine);
	EXPECT_EQ(loadCalibration(dir_ + "/seq.toml").calibration.mapping.x,
		  loadCalibration(dir_ + "/sim.toml").calibration.mapping.x);
}

TEST_F(CalibrateTool, FailedCalibrationLeavesTheGoodFile)
{
	ASSERT_EQ(sim_.status, 0) << sim_.out;
	std::string good = dir_ + "/sim.toml";
	std::ifstream before(good);
	std::stringstream text;
	text << before.rdbuf();
	// Too few views to hold any out.
	ToolRun run = calibrate("--sequence " + dir_ + "/seq --step 9 --output " + good);
	EXPECT_EQ(run.status, 1) << run.out;
	EXPECT_NE(run.out.find("calibration failed"), std::string::npos) << run.out;
	EXPECT_NE(run.out.find(good + " left unchanged"), std::string::npos) << run.out;
	std::ifstream after(good);
	std::stringstream again;
	again << after.rdbuf();
	EXPECT_EQ(again.str(), text.str());
}

// The HIL suite's webcam is 320x180 (tests/hil/guest/faults.sh): --sim
// calibrates that camera, and as well in its own pixels.
TEST_F(CalibrateTool, SimulatorCalibratesAnotherColourSize)
{
	ToolRun run = calibrate("--sim --sim-colour-size 320x180 --output " + dir_ + "/small.toml");
	ASSERT_EQ(run.status, 0) << run.out;
	CalibrationResult loaded = loadCalibration(dir_ + "/small.toml");
	ASSERT_TRUE(loaded.ok());
	EXPECT_EQ(loaded.calibration.colourCamera, "sim colour 320x180 seed 1");
	EXPECT_EQ(loaded.calibration.mapping.colourWidth, 320);
	EXPECT_EQ(loaded.calibration.mapping.colourHeight, 180);
	TruthReport truth = compareWithTruth(loaded.calibration.mapping, 320, 180);
	print("parallax at 320x180", truth);
	EXPECT_LE(truth.overall.rmsPx, 0.5);
}

TEST(CalibrateToolOptions, BadColourSizeIsAUsageError)
{
	for (const char *size : { "8x8", "320", "4000x3000", "320x180x2" }) {
		ToolRun run = calibrate(std::string("--sim --sim-colour-size ") + size + " --output /tmp/never.toml");
		EXPECT_EQ(run.status, 2) << size;
		EXPECT_NE(run.out.find(std::string("--sim-colour-size has a bad value: ") + size), std::string::npos)
			<< run.out;
	}
}

TEST(CalibrateToolOptions, MissingSourceIsAUsageError)
{
	ToolRun run = calibrate("--output /tmp/never.toml");
	EXPECT_EQ(run.status, 2);
	EXPECT_NE(run.out.find("give one of --sim, --sequence DIR"), std::string::npos) << run.out;
}

TEST(CalibrateToolOptions, MissingSequenceNamesTheFile)
{
	ToolRun run = calibrate("--sequence /nonexistent --output /tmp/never.toml");
	EXPECT_EQ(run.status, 1);
	EXPECT_NE(run.out.find("/nonexistent/rgb.txt"), std::string::npos) << run.out;
}

} // namespace
} // namespace depthkey
