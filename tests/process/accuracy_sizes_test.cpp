// Issue 28's accuracy rows at the sizes people buy: the gate of
// accuracy_gate_test.cpp (seeds 1-3, every artefact, 300 frames, shipped
// defaults) at 1280x720 and 1920x1080, each calibrated for its size with
// depthkey-calibrate --sim --sim-colour-size. Boundary F at 2 px and at a
// tolerance scaled with the width (2 px per 640: 4 px at 1280, 6 px at 1920).
// Several minutes (a 1080p frame is keyed and scored at a few frames a
// second here), so its own make target, `make accuracy-sizes`, which sets
// DEPTHKEY_ACCURACY_SIZES=1; otherwise reported skipped.
// What is asserted: a regression floor at today's figures, a little below.
// The targets (mean IoU >= 0.97, every seed >= 0.955) are printed.
#include "tests/process/shell_command.hpp"
#include "tests/test_paths.hpp"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <string>
#include <unistd.h>

using depthkey::test::lastLine;
using depthkey::test::run;

namespace {

struct SizeScores {
	double iou = 0, bf = 0, bfScaled = 0;
};

struct SizeFloor {
	int width, height;
	SizeScores seeds[3];
};

SizeScores evaluate(const std::string &command)
{
	int status;
	const std::string out = run(command, status);
	EXPECT_EQ(status, 0) << out;
	SizeScores s;
	EXPECT_EQ(std::sscanf(lastLine(out).c_str(),
			      "summary method=pipeline frames=300 iou=%lf bf=%lf fnr=%*f fpr=%*f fps=%*f bf_scaled=%lf",
			      &s.iou, &s.bf, &s.bfScaled),
		  3)
		<< out;
	return s;
}

void gateAt(const SizeFloor &floor)
{
	namespace fs = std::filesystem;
	const std::string size = std::to_string(floor.width) + "x" + std::to_string(floor.height);
	const fs::path dir = fs::temp_directory_path() / ("depthkey-gate-" + size + "-" + std::to_string(getpid()));
	fs::create_directories(dir);
	const std::string bin = depthkey::test::binDir();
	int status;
	const std::string fit = run(bin + "/depthkey-calibrate --sim --sim-colour-size " + size + " --output " +
					    (dir / "calibration.toml").string(),
				    status);
	ASSERT_EQ(status, 0) << fit;
	{
		std::ofstream config(dir / "gate.toml");
		config << "[mapping]\ncalibration_file = \"" << (dir / "calibration.toml").string() << "\"\n"
		       << "[colour]\nwidth = " << floor.width << "\nheight = " << floor.height << "\n";
	}
	SizeScores seeds[3], mean;
	for (int s = 0; s < 3; ++s) {
		seeds[s] = evaluate(bin + "/depthkey-eval --config " + (dir / "gate.toml").string() + " --sim " +
				    std::to_string(s + 1) + " --frames 300");
		mean.iou += seeds[s].iou / 3;
		mean.bf += seeds[s].bf / 3;
		mean.bfScaled += seeds[s].bfScaled / 3;
	}
	fs::remove_all(dir);
	const int scaledPx = (2 * floor.width + 320) / 640;
	std::printf("%s, all artefacts   IoU    BF(2 px) BF(%d px)\n", size.c_str(), scaledPx);
	for (int s = 0; s < 3; ++s) {
		std::printf("  seed %d            %.3f  %.3f    %.3f\n", s + 1, seeds[s].iou, seeds[s].bf,
			    seeds[s].bfScaled);
		EXPECT_GE(seeds[s].iou, floor.seeds[s].iou) << size << " seed " << s + 1;
		EXPECT_GE(seeds[s].bf, floor.seeds[s].bf) << size << " seed " << s + 1;
		EXPECT_GE(seeds[s].bfScaled, floor.seeds[s].bfScaled) << size << " seed " << s + 1;
	}
	std::printf("  mean              %.3f  %.3f    %.3f\n", mean.iou, mean.bf, mean.bfScaled);
	const bool met = mean.iou >= 0.97 && seeds[0].iou >= 0.955 && seeds[1].iou >= 0.955 && seeds[2].iou >= 0.955;
	std::printf("issue 28 target at %s: mean IoU >= 0.97, every seed >= 0.955: %s\n", size.c_str(),
		    met ? "met" : "NOT met");
}

bool asked()
{
	const char *v = std::getenv("DEPTHKEY_ACCURACY_SIZES");
	return v && std::string(v) == "1";
}

} // namespace

// Floors: the figures of 7 December (the cut coarse to fine), less 0.005
// (IoU) and 0.01 (BF).
TEST(AccuracySizes, PipelineAt1280x720)
{
	if (!asked())
		GTEST_SKIP() << "minutes long: make accuracy-sizes (DEPTHKEY_ACCURACY_SIZES=1)";
	gateAt({ 1280, 720, { { 0.981, 0.893, 0.914 }, { 0.962, 0.760, 0.840 }, { 0.963, 0.778, 0.876 } } });
}

TEST(AccuracySizes, PipelineAt1920x1080)
{
	if (!asked())
		GTEST_SKIP() << "minutes long: make accuracy-sizes (DEPTHKEY_ACCURACY_SIZES=1)";
	gateAt({ 1920, 1080, { { 0.968, 0.838, 0.876 }, { 0.960, 0.712, 0.831 }, { 0.959, 0.622, 0.854 } } });
}
