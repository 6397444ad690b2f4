// Issue 11's accuracy gate, run the way a developer runs it: depthkey-calibrate
// fits the simulator's rig, depthkey-eval scores the pipeline on 300 frames
// of the simulated lecture, shipped defaults, calibrated:
//   - seeds 1, 2 and 3 with every artefact on (ToF noise up to 30 cm at the
//     edge, halo, motion blur, free-running cameras with 40 ms depth
//     latency, lens distortion, parallax, colour noise, a desk and monitor
//     in the lecturer's depth range, changing board and light);
//   - seed 1 with a clean depth camera (no latency, jitter, halo, noise or
//     blur; depth at 25 fps).
// What is asserted:
//   - the pipeline is clearly better than depth-only on seed 1 (IoU at
//     least twice, boundary F at least four times the baseline's);
//   - a regression floor at what it scores today (the simulator and the
//     pipeline are deterministic integer code, so the same on any machine),
//     a little below, per run and for the mean.
// The targets (mean IoU >= 0.97 and BF >= 0.90, every seed IoU >=
// 0.95; clean IoU >= 0.98 and BF >= 0.93) are printed, not asserted: they
// are not met yet (docs/accuracy.md).
#include "tests/process/shell_command.hpp"
#include "tests/test_paths.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <string>

using depthkey::test::lastLine;
using depthkey::test::run;

namespace {

struct Scores {
	double iou = 0, bf = 0;
};

Scores evaluate(const std::string &eval, const std::string &method)
{
	int status;
	std::string out = run(eval + " --method " + method, status);
	EXPECT_EQ(status, 0) << out;
	Scores s;
	std::string summary = lastLine(out);
	std::string format = "summary method=" + method + " frames=300 iou=%lf bf=%lf";
	EXPECT_EQ(std::sscanf(summary.c_str(), format.c_str(), &s.iou, &s.bf), 2) << out;
	std::printf("%s\n", out.c_str());
	return s;
}

} // namespace

TEST(AccuracyGate, PipelineOnTheSimulatedLecture)
{
	namespace fs = std::filesystem;
	const fs::path dir = fs::temp_directory_path() / ("depthkey-gate-" + std::to_string(getpid()));
	fs::create_directories(dir);
	const std::string bin = depthkey::test::binDir();
	int status;
	std::string fit = run(bin + "/depthkey-calibrate --sim --output " + (dir / "calibration.toml").string(), status);
	ASSERT_EQ(status, 0) << fit;
	const std::string mapping = "[mapping]\ncalibration_file = \"" + (dir / "calibration.toml").string() + "\"\n";
	{
		// The shipped defaults, calibrated.
		std::ofstream config(dir / "gate.toml");
		config << mapping;
		// The same with a clean depth camera at 25 fps.
		std::ofstream clean(dir / "clean.toml");
		clean << mapping << "[depth]\nfps = 25\n[sim]\ndepth_latency_ms = 0.0\ndepth_jitter_ms = 0.0\n"
		      << "colour_jitter_ms = 0.0\nhalo_width_px = 0\ndepth_noise = false\nmotion_blur = false\n";
	}
	auto eval = [&](const char *config, int seed) {
		return bin + "/depthkey-eval --config " + (dir / config).string() + " --sim " + std::to_string(seed) +
		       " --frames 300";
	};
	const Scores depthOnly = evaluate(eval("gate.toml", 1), "depth-only");
	Scores seeds[3], mean;
	for (int s = 0; s < 3; ++s) {
		seeds[s] = evaluate(eval("gate.toml", s + 1), "pipeline");
		mean.iou += seeds[s].iou / 3;
		mean.bf += seeds[s].bf / 3;
	}
	const Scores clean = evaluate(eval("clean.toml", 1), "pipeline");
	fs::remove_all(dir);

	EXPECT_GE(seeds[0].iou, 2.0 * depthOnly.iou);
	EXPECT_GE(seeds[0].bf, 4.0 * depthOnly.bf);
	// Floors: today's figures (0.987/0.940, 0.971/0.900, 0.967/0.902; clean
	// 0.990/0.967: the cut solved coarse to fine, issue 28; before it
	// 0.985/0.927, 0.966/0.880, 0.966/0.903 and 0.989/0.961), less 0.005
	// (IoU) and 0.01 (BF) per seed; the means (0.975/0.914) above the issue's
	// targets, which they meet.
	const Scores floors[3] = { { 0.982, 0.930 }, { 0.966, 0.890 }, { 0.962, 0.892 } };
	for (int s = 0; s < 3; ++s) {
		EXPECT_GE(seeds[s].iou, floors[s].iou) << "seed " << s + 1;
		EXPECT_GE(seeds[s].bf, floors[s].bf) << "seed " << s + 1;
	}
	EXPECT_GE(mean.iou, 0.972);
	EXPECT_GE(mean.bf, 0.905);
	EXPECT_GE(clean.iou, 0.985);
	EXPECT_GE(clean.bf, 0.957);

	std::printf("%-30s %s\n", "run", "IoU    BF");
	for (int s = 0; s < 3; ++s)
		std::printf("seed %d, all artefacts           %.3f  %.3f\n", s + 1, seeds[s].iou, seeds[s].bf);
	std::printf("mean of seeds 1-3              %.3f  %.3f\n", mean.iou, mean.bf);
	std::printf("seed 1, clean depth at 25 fps  %.3f  %.3f\n", clean.iou, clean.bf);
	const bool seedsMet = mean.iou >= 0.97 && mean.bf >= 0.90 && seeds[0].iou >= 0.95 && seeds[1].iou >= 0.95 &&
			      seeds[2].iou >= 0.95;
	std::printf("issue 11 target mean IoU >= 0.97, BF >= 0.90, every seed IoU >= 0.95: %s\n",
		    seedsMet ? "met" : "NOT met");
	std::printf("issue 11 target clean depth IoU >= 0.98, BF >= 0.93: %s\n",
		    clean.iou >= 0.98 && clean.bf >= 0.93 ? "met" : "NOT met");
}
