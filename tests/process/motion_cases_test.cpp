// Issue 29 section 6, the student's view in motion, the moments found in
// the simulated lecture scored the way depthkey-eval scores them (shipped
// defaults, calibrated by depthkey-calibrate --sim). The accuracy gate scores
// the first 12 s; these lie later in the lecture's 27.5 s cycle.
//   - Seed 1, 20.0-21.2 s: he writes the third block standing behind the
//     desk; the desk and the monitor were keyed in beside him (mean IoU
//     0.552, worst 0.506 on main; 0.982 and 0.973 with algo/furniture_mask.hpp
//     cutting the desk off his depth area and its evidence, docs/accuracy.md).
//   - Seed 1, 14.2-16.0 s: he writes the second block's second line; the
//     writing hand touches the board, and depth says board there as surely
//     as on the board: the hand is lost (recall of the lecturer around it
//     0.843, worst frame 0.654 on main). Disabled: the fix found (colour's
//     sure verdict holding depth's board term in FusedEvidence::fuse, recall
//     0.994) let the desk back in (the test above: 0.982 -> 0.942), since
//     the furniture's "surely board" evidence is the board's own value 1
//     (docs/accuracy.md, "The student's view in motion").
#include "hal/image_file_reader.hpp"
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

// A scratch directory with the simulator's calibration (depthkey-calibrate
// --sim) and a config that uses it, the shipped defaults otherwise.
struct CalibratedDir {
	std::filesystem::path dir;
	std::string bin = depthkey::test::binDir();
	std::string config;

	explicit CalibratedDir(const char *name, std::string &error)
	{
		dir = std::filesystem::temp_directory_path() / (std::string(name) + std::to_string(getpid()));
		std::filesystem::create_directories(dir);
		int status;
		std::string fit =
			run(bin + "/depthkey-calibrate --sim --output " + (dir / "calibration.toml").string(), status);
		if (status != 0)
			error = fit;
		config = (dir / "motion.toml").string();
		std::ofstream(config) << "[mapping]\ncalibration_file = \"" << (dir / "calibration.toml").string()
				      << "\"\n";
	}
	~CalibratedDir() { std::filesystem::remove_all(dir); }

	// depthkey-eval on a simulated seed with more arguments; its output.
	std::string eval(int seed, long frames, const std::string &more, int &status) const
	{
		return run(bin + "/depthkey-eval --config " + config + " --sim " + std::to_string(seed) +
				   " --frames " + std::to_string(frames) + " " + more,
			   status);
	}
};

// One grey or RGB picture of depthkey-eval --preview (its first channel).
std::vector<uint8_t> previewMask(const std::filesystem::path &png, int &width)
{
	depthkey::DecodedImage image;
	std::string error;
	if (depthkey::decodeImageFile(png.string(), { 4096, 4096 }, image, error) < 0) {
		ADD_FAILURE() << error;
		return {};
	}
	width = image.width;
	std::vector<uint8_t> mask(size_t(image.width) * image.height);
	for (size_t i = 0; i < mask.size(); ++i)
		mask[i] = image.pixels[i * size_t(image.channels)];
	return mask;
}

} // namespace

TEST(MotionCases, DeskAndMonitorAreNotKeyedInBesideHim)
{
	std::string error;
	const CalibratedDir cal("depthkey-motion-", error);
	ASSERT_EQ(error, "");
	const std::filesystem::path dir = cal.dir;
	int status;
	// 25 colour frames a second: frames 500-529 are 20.0-21.2 s.
	std::string out = cal.eval(1, 530, "--csv " + (dir / "frames.csv").string(), status);
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
}

TEST(MotionCases, WritingHandIsKeptWhereItTouchesTheBoard)
{
	std::string error;
	const CalibratedDir cal("depthkey-hand-", error);
	ASSERT_EQ(error, "");
	const std::filesystem::path preview = cal.dir / "preview";
	int status;
	// Frames 355-400 (14.2-16.0 s), every fifth: the truth and the alpha.
	std::string out = cal.eval(1, 401, "--preview " + preview.string() + " --preview-every 5", status);
	ASSERT_EQ(status, 0) << out;
	// Where the hand writes the second line (x 250-420, y 60-170 of
	// 640x480): the hand and the forearm, and his head coming in from the
	// left late in the line (kept either way).
	const int x0 = 250, x1 = 420, y0 = 60, y1 = 170;
	long kept = 0, lost = 0;
	double worst = 1;
	for (int frame = 355; frame <= 400; frame += 5) {
		char prefix[32];
		std::snprintf(prefix, sizeof(prefix), "frame%06d-", frame);
		int width = 0, alphaWidth = 0;
		const std::vector<uint8_t> truth = previewMask(preview / (std::string(prefix) + "truth.png"), width);
		const std::vector<uint8_t> alpha = previewMask(preview / (std::string(prefix) + "alpha.png"), alphaWidth);
		ASSERT_EQ(width, 640) << prefix;
		ASSERT_EQ(alphaWidth, 640) << prefix;
		ASSERT_EQ(alpha.size(), truth.size()) << prefix;
		long frameKept = 0, frameLost = 0;
		for (int y = y0; y < y1; ++y)
			for (int x = x0; x < x1; ++x) {
				const size_t i = size_t(y) * 640 + x;
				if (truth[i] >= 128)
					++(alpha[i] >= 128 ? frameKept : frameLost);
			}
		ASSERT_GT(frameKept + frameLost, 1000) << prefix << ": the hand is not in the box";
		kept += frameKept;
		lost += frameLost;
		worst = std::min(worst, double(frameKept) / double(frameKept + frameLost));
	}
	const double recall = double(kept) / double(kept + lost);
	std::printf("seed 1, 14.2-16.0 s, the hand on the board: recall %.3f (%ld of his pixels lost), worst frame %.3f\n",
		    recall, lost, worst);
	// Before the hold of depth's board term where the colour moved (main of
	// 7 December): recall 0.843, worst frame 0.654. With it: 0.976 and
	// 0.806 (the worst frame is a still moment: the chalk held against the
	// board, where only depth and the previous frame speak). The floors are
	// what is reached; the target is each frame >= 0.95.
	// The depth offset measured and applied once a second (pairing.offset_ms
	// "auto") moves the recall: with the accumulated estimate (issue 29 §3,
	// -41.2 ms measured, the truth -40) it is 0.960; fixed at -38 ms (what
	// the sliding-window estimate ended at) 0.976, at -42 ms 0.961.
	// With the hold through still moments (FusedEvidence::kHoldFrames, 7
	// December): recall 0.994, worst frame 0.990 (frames 360 and 385, the
	// chalk held still, were 0.806 and 0.806). The targets are met and are
	// the floors.
	std::printf("    target: recall >= 0.97 (%s), every frame >= 0.95 (%s)\n", recall >= 0.97 ? "met" : "NOT met",
		    worst >= 0.95 ? "met" : "NOT met");
	EXPECT_GE(recall, 0.97);
	EXPECT_GE(worst, 0.95);
}
