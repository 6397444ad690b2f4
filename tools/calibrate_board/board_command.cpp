// depthkey-calibrate --board: writes the circle pattern for the board's
// computer to show full screen, finds it in a colour picture of the board
// (the simulator's, or a still from the colour camera), fits the homography
// colour px -> board px, reports the reprojection error in board pixels and
// writes the board calibration file, unless the fit is over --max-rms.
//
//   depthkey-calibrate --board --write-board-pattern FILE [--board-size WxH]
//   depthkey-calibrate --board (--sim [--seed N] [--no-distortion] | --image FILE)
//                      [--board-size WxH] [--output FILE] [--max-rms PX]
//
// Last line, for scripts: summary board rms_px=R max_px=M
#include "tools/calibrate_board/board_command.hpp"

#include "algo/board_calibration.hpp"
#include "algo/board_pattern.hpp"
#include "config/board_calibration_file.hpp"
#include "hal/image_file.hpp"
#include "hal/sim/board_display.hpp"
#include "hal/sim/lecture_simulator.hpp"
#include "settings/settings.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <string>

namespace depthkey {

bool parseSize(const char *text, int &w, int &h, int maxW, int maxH)
{
	char x;
	int end = 0; // nothing may follow: "320x180x2" is not a size
	return std::sscanf(text, "%d%c%d%n", &w, &x, &h, &end) == 3 && text[end] == '\0' && (x == 'x' || x == 'X') &&
	       w >= 16 && h >= 16 && w <= maxW && h <= maxH;
}

namespace {

struct BoardOptions {
	bool sim = false;
	uint64_t seed = 1;
	bool distortion = true;
	std::string image;
	std::string patternFile;
	std::string output;
	int boardWidth = 1920, boardHeight = 1080;
	bool boardSizeGiven = false;
	int colourWidth = 640, colourHeight = 480;
	GridSize grid{ 9, 5 };
	double fill = 0.55;
	double maxRmsPx = 2.0;
};

void usage(FILE *out)
{
	std::fprintf(out, "usage (depthkey-calibrate --help has every form):\n");
	printBoardUsage(out);
}

} // namespace

void printBoardUsage(FILE *out)
{
	std::fprintf(out,
		     "       depthkey-calibrate --board --write-board-pattern FILE [--board-size WxH]\n"
		     "       depthkey-calibrate --board (--sim [--seed N] [--no-distortion] [--colour-size WxH]\n"
		     "                                   | --image COLOUR.png)\n"
		     "                          [--board-size WxH] [--grid COLSxROWS] [--fill F]\n"
		     "                          [--output FILE] [--max-rms PX]\n");
}

namespace {

int parse(int argc, char **argv, BoardOptions &o)
{
	for (int i = 1; i < argc; i++) {
		std::string a = argv[i];
		auto value = [&]() -> const char * { return i + 1 < argc ? argv[++i] : nullptr; };
		const char *v = nullptr;
		bool ok = true;
		if (a == "--board")
			continue;
		if (a == "--sim")
			o.sim = true;
		else if (a == "--no-distortion")
			o.distortion = false;
		else if (a == "-h" || a == "--help") {
			usage(stdout);
			std::exit(0);
		} else if (!(v = value()))
			ok = false;
		else if (a == "--seed")
			o.seed = std::strtoull(v, nullptr, 10);
		else if (a == "--image")
			o.image = v;
		else if (a == "--write-board-pattern")
			o.patternFile = v;
		else if (a == "--output")
			o.output = v;
		else if (a == "--board-size")
			ok = o.boardSizeGiven = parseSize(v, o.boardWidth, o.boardHeight, 3840, 2160);
		else if (a == "--colour-size")
			ok = parseSize(v, o.colourWidth, o.colourHeight, 1920, 1080);
		else if (a == "--grid")
			ok = parseSize(v, o.grid.cols, o.grid.rows, 1000, 1000) || (std::sscanf(v, "%dx%d", &o.grid.cols, &o.grid.rows) == 2 && o.grid.cols >= 3 && o.grid.rows >= 3);
		else if (a == "--fill")
			ok = (o.fill = std::atof(v)) >= 0.2 && o.fill <= 0.95;
		else if (a == "--max-rms")
			ok = (o.maxRmsPx = std::atof(v)) > 0;
		else
			ok = false;
		if (!ok) {
			std::fprintf(stderr, "depthkey-calibrate: bad or unknown option %s%s%s\n", a.c_str(), v ? " " : "", v ? v : "");
			usage(stderr);
			return 2;
		}
	}
	if (o.patternFile.empty() && o.sim == !o.image.empty()) {
		std::fprintf(stderr, "depthkey-calibrate: --board needs --write-board-pattern FILE, or one of --sim and --image FILE\n");
		usage(stderr);
		return 2;
	}
	// The simulated display's pixels are square: its height follows the width.
	if (o.sim && !o.boardSizeGiven)
		o.boardHeight = simBoardHeight(o.boardWidth);
	return 0;
}

std::string utcNow()
{
	std::time_t t = std::time(nullptr);
	std::tm tm{};
	gmtime_r(&t, &tm);
	char buf[32];
	std::strftime(buf, sizeof(buf), "%Y-%m-%dT%H:%M:%SZ", &tm);
	return buf;
}

int writePattern(const BoardPattern &pattern, const std::string &path)
{
	RgbImage picture;
	pattern.render(picture);
	std::string error;
	if (writePng(path, picture, error) < 0) {
		std::fprintf(stderr, "depthkey-calibrate: cannot write the pattern image: %s\n", error.c_str());
		return 1;
	}
	std::printf("wrote the board pattern %s: %dx%d px, %dx%d circles %.0f px apart; show it full screen on the board\n",
		    path.c_str(), pattern.boardWidth, pattern.boardHeight, pattern.grid.cols, pattern.grid.rows,
		    pattern.spacingPx());
	return 0;
}

// The simulator's colour camera looking at its board's display showing the
// pattern: nobody in front of it, the desk moved aside (a technician clears
// the view before the shot).
void renderSimShot(const BoardOptions &o, const BoardPattern &pattern, LectureSimulator &simulator, ColourFrame &colour)
{
	SimSettings s;
	s.seed = o.seed;
	s.distortion = o.distortion;
	s.table = false;
	simulator.configure(s, o.colourWidth, o.colourHeight);
	simulator.setLecturerVisible(false);
	RgbImage picture;
	pattern.render(picture);
	simulator.showOnBoard(picture);
	simulator.renderColour(1.0, colour);
}

// The fitted H against the simulator's own mapping, over every 4th colour
// pixel that sees the display.
void reportSimTruth(const BoardOptions &o, const LectureSimulator &simulator, const BoardFit &fit)
{
	const double d = simulator.settings().boardDistanceMm / 1000.0;
	double sum = 0, worst = 0;
	int n = 0;
	for (int y = 0; y < o.colourHeight; y += 4)
		for (int x = 0; x < o.colourWidth; x += 4) {
			double tu, tv, ix, iy, u, v;
			if (!simColourToBoard(simulator.rig(), d, o.boardWidth, o.boardHeight, x, y, tu, tv) ||
			    tu < -0.5 || tv < -0.5 || tu > o.boardWidth - 0.5 || tv > o.boardHeight - 0.5 ||
			    !fit.lens.undistort(x, y, ix, iy) || !fit.colourToBoard.apply(ix, iy, u, v))
				continue;
			double e = std::hypot(u - tu, v - tv);
			sum += e * e;
			worst = std::max(worst, e);
			n++;
		}
	std::printf("against the simulator's truth (%s): rms %.3f board px, max %.3f over %d points of the display the camera sees\n",
		    o.distortion ? "lens distortion on: the fitted lens, then H" : "pinhole lens: the true H exists",
		    n ? std::sqrt(sum / n) : 0.0, worst, n);
	if (!o.distortion) {
		Homography truth = simTrueHomography(simulator.rig(), d, o.boardWidth, o.boardHeight);
		std::printf("true H:   ");
		for (double v : truth.h)
			std::printf(" %.6g", v);
		std::printf("\nfitted H: ");
		for (double v : fit.colourToBoard.h)
			std::printf(" %.6g", v);
		std::printf("\n");
	}
}

BoardCalibration calibrationOf(const BoardFit &fit, int colourWidth, int colourHeight, int boardWidth, int boardHeight)
{
	BoardCalibration c;
	c.colourToBoard = fit.colourToBoard;
	c.lensK1 = fit.lens.k1;
	c.lensK2 = fit.lens.k2;
	c.colourWidth = colourWidth;
	c.colourHeight = colourHeight;
	c.boardWidth = boardWidth;
	c.boardHeight = boardHeight;
	c.date = utcNow();
	c.points = fit.points;
	c.rmsPx = fit.rmsPx;
	c.maxPx = fit.maxPx;
	return c;
}

} // namespace

int fitSimBoardCalibration(uint64_t seed, int colourWidth, int colourHeight, int boardWidth, BoardCalibration &out,
			   std::string &error)
{
	BoardOptions o;
	o.sim = true;
	o.seed = seed;
	o.colourWidth = colourWidth;
	o.colourHeight = colourHeight;
	o.boardWidth = boardWidth;
	o.boardHeight = simBoardHeight(boardWidth);
	BoardPattern pattern{ o.boardWidth, o.boardHeight, o.grid, o.fill };
	LectureSimulator simulator;
	ColourFrame colour;
	renderSimShot(o, pattern, simulator, colour);
	BoardFit fit;
	std::vector<ImagePoint> found;
	if (calibrateBoard(colour.rgb, pattern, fit, found, error) < 0)
		return -EINVAL;
	if (fit.rmsPx > o.maxRmsPx) {
		error = "the board fit's rms " + std::to_string(fit.rmsPx) + " board px is over " + std::to_string(o.maxRmsPx);
		return -ERANGE;
	}
	out = calibrationOf(fit, colourWidth, colourHeight, o.boardWidth, o.boardHeight);
	return 0;
}

bool wantsBoardCalibration(int argc, char **argv)
{
	for (int i = 1; i < argc; i++)
		if (std::strcmp(argv[i], "--board") == 0)
			return true;
	return false;
}

int runBoardCalibration(int argc, char **argv)
{
	BoardOptions o;
	if (int ret = parse(argc, argv, o))
		return ret;
	BoardPattern pattern{ o.boardWidth, o.boardHeight, o.grid, o.fill };
	if (!o.patternFile.empty()) {
		if (int ret = writePattern(pattern, o.patternFile))
			return ret;
		if (!o.sim && o.image.empty())
			return 0;
	}

	LectureSimulator simulator;
	ColourFrame colour;
	std::string error;
	if (o.sim) {
		renderSimShot(o, pattern, simulator, colour);
		std::printf("source: the simulator's colour camera (seed %llu, lens distortion %s), %dx%d, its board showing the pattern\n",
			    static_cast<unsigned long long>(o.seed), o.distortion ? "on" : "off", o.colourWidth, o.colourHeight);
	} else if (readRgbImage(o.image, colour.rgb, error) < 0) {
		std::fprintf(stderr, "depthkey-calibrate: %s\n", error.c_str());
		return 1;
	} else {
		std::printf("source: %s, %dx%d\n", o.image.c_str(), colour.rgb.width(), colour.rgb.height());
	}
	std::printf("pattern: %dx%d circles %.0f px apart on a %dx%d board picture\n", o.grid.cols, o.grid.rows,
		    pattern.spacingPx(), o.boardWidth, o.boardHeight);

	BoardFit fit;
	std::vector<ImagePoint> found;
	if (calibrateBoard(colour.rgb, pattern, fit, found, error) < 0) {
		std::fprintf(stderr, "depthkey-calibrate: %s\n", error.c_str());
		return 1;
	}
	std::printf("found all %d circles; homography (RANSAC, %.0f px): %d inliers\n", fit.points, kBoardRansacPx,
		    fit.inliers);
	std::printf("colour lens: k1 %.5f k2 %.5f (radial, at a focal length of one image width)%s\n", fit.lens.k1,
		    fit.lens.k2, fit.lens.isPinhole() ? ": a pinhole fits best" : "");
	std::printf("reprojection error: rms %.3f board px, max %.3f board px\n", fit.rmsPx, fit.maxPx);
	if (o.sim)
		reportSimTruth(o, simulator, fit);

	int status = 0;
	if (fit.rmsPx > o.maxRmsPx) {
		std::printf("refused: rms %.3f board px is over --max-rms %.3f%s\n", fit.rmsPx, o.maxRmsPx,
			    o.output.empty() ? "" : ("; " + o.output + " left as it was").c_str());
		status = 1;
	} else if (!o.output.empty()) {
		BoardCalibration c = calibrationOf(fit, colour.rgb.width(), colour.rgb.height(), o.boardWidth, o.boardHeight);
		if (writeBoardCalibration(o.output, c, error) < 0) {
			std::fprintf(stderr, "depthkey-calibrate: %s\n", error.c_str());
			status = 1;
		} else {
			std::printf("wrote %s\n", o.output.c_str());
		}
	}
	std::printf("summary board rms_px=%.3f max_px=%.3f\n", fit.rmsPx, fit.maxPx);
	return status;
}

} // namespace depthkey
