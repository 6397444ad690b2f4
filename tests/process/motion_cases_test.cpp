// Issue 29 section 6, the student's view in motion, the moments found in
// the simulated lecture scored the way depthkey-eval scores them (shipped
// defaults, calibrated by depthkey-calibrate --sim). The accuracy gate scores
// the first 12 s; these lie later in the lecture's 27.5 s cycle.
//   - Seed 1, 20.0-21.2 s: he writes the third block standing behind the
//     desk; the desk and the monitor were keyed in beside him (mean IoU
//     0.552, worst 0.506 on main; 0.982 and 0.973 with algo/furniture_mask.hpp
//     cutting the desk off his depth area and its evidence, docs/accuracy.md).
#include "tests/process/shell_command.hpp"
#include "tests/test_paths.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <string>
#include <vector>

using depthkey::test::run;

namespace {

// depthkey-eval's per-frame IoU (--csv), in frame order.
std::vector<double> frameIous(const std::filesystem::path &csv)
{
	std::ifstream in(csv);
	std::string line;
	std::vector<double> ious;
	std::getline(in, line); // header
	while (std::getline(in, line)) {
		long frame;
		unsigned long long colourNs, depthNs;
		double iou;
		if (std::sscanf(line.c_str(), "%ld,%llu,%llu,%lf", &frame, &colourNs, &depthNs, &iou) == 4)
			ious.push_back(iou);
		else
			ious.push_back(-1.0); // an unscored frame (nothing paired yet)
	}
	return ious;
}

} // namespace

TEST(MotionCases, DeskAndMonitorAreNotKeyedInBesideHim)
{
	namespace fs = std::filesystem;
	const fs::path dir = fs::temp_directory_path() / ("depthkey-motion-" + std::to_string(getpid()));
	fs::create_directories(dir);
	const std::string bin = depthkey::test::binDir();
	int status;
	std::string fit = run(bin + "/depthkey-calibrate --sim --output " + (dir / "calibration.toml").string(), status);
	ASSERT_EQ(status, 0) << fit;
	std::ofstream(dir / "motion.toml") << "[mapping]\ncalibration_file = \"" << (dir / "calibration.toml").string()
					   << "\"\n";
	// 25 colour frames a second: frames 500-529 are 20.0-21.2 s.
	std::string out = run(bin + "/depthkey-eval --config " + (dir / "motion.toml").string() +
				      " --sim 1 --frames 530 --csv " + (dir / "frames.csv").string(),
			      status);
	ASSERT_EQ(status, 0) << out;
	const std::vector<double> ious = frameIous(dir / "frames.csv");
	ASSERT_EQ(ious.size(), 530u) << out;
	double sum = 0, worst = 1;
	for (size_t n = 500; n < 530; ++n) {
		sum += ious[n];
		worst = std::min(worst, ious[n]);
	}
	std::printf("seed 1, 20.0-21.2 s, behind the desk: mean IoU %.3f, worst %.3f\n", sum / 30, worst);
	EXPECT_GE(sum / 30, 0.96);
	EXPECT_GE(worst, 0.95);
	fs::remove_all(dir);
}
