// depthkey-calibrate: fits the depth -> colour mapping from views of a
// circle pattern seen by both cameras and writes the calibration file.
//
//   depthkey-calibrate (--sim | --sequence DIR | --live [--config FILE]) --output FILE [options]
//   depthkey-calibrate --print-pattern FILE.pdf|FILE.svg [--paper a4|a3|a2|a1]
//   depthkey-calibrate --board ... (tools/calibrate_board/)
//
// For each step of the plan (or each frame of a sequence) it says where the
// pattern should be, finds the grid in both cameras, and says whether the
// view was accepted and, if not, which camera did not see the pattern. It
// then fits both models, prints their residuals per depth on the views used
// and on the held-out views, and writes the better one (or --model's). The
// last line is for scripts:
//   summary model=parallax rms_px=0.31 max_px=1.20 heldout_rms_px=0.35
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <iostream>
#include <string>
#include <sys/stat.h>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "algo/calibration_fit.hpp"
#include "algo/calibration_plan.hpp"
#include "algo/circle_grid_detector.hpp"
#include "config/calibration_file.hpp"
#include "hal/image_file.hpp"
#include "hal/recording/sequence_reader.hpp"
#include "hal/recording/sequence_writer.hpp"
#include "hal/sim/calibration_pattern.hpp"
#include "tools/calibrate_board/board_command.hpp"
#include "tools/calibrate_live/live_view_source.hpp"
#include "tools/calibrate_print/print_command.hpp"

using namespace depthkey;

namespace {

struct Options {
	bool sim = false;
	uint64_t seed = 1;
	bool depthNoise = true;
	int simBoardWidth = 1920;     // --sim also fits the simulated board (its [board]); 0 = not
	int simColourWidth = 640, simColourHeight = 480; // --sim-colour-size: the camera's size
	std::string sequence;
	int step = 1;
	std::string output;
	std::optional<MappingKind> model;
	int holdOutEvery = 4;
	std::optional<double> holdOutDepth;
	std::vector<double> depths = defaultCalibrationDepths();
	bool depthsGiven = false; // --live leaves out the default depths behind the board
	GridSize grid;
	std::string preview;
	std::string record;
	double maxRmsPx = 2.0;
	bool interactive = false;
	bool live = false;            // the configured cameras (tools/calibrate_live/)
	std::string config;           // --config: the daemon's config to take them from
	double viewTimeoutS = 60;
};

void usage(FILE *out)
{
	std::fprintf(out,
		     "usage: depthkey-calibrate (--sim [--seed N] [--no-depth-noise] [--sim-board-width N]\n"
		     "                                 [--sim-colour-size WxH] |\n"
		     "                           --sequence DIR [--step N] |\n"
		     "                           --live [--config FILE] [--view-timeout S])\n"
		     "                          --output FILE [--model paper|parallax]\n"
		     "                          [--hold-out-every K | --hold-out-depth METRES]\n"
		     "                          [--depths M,M,...] [--grid COLSxROWS] [--max-rms PX]\n"
		     "                          [--preview DIR] [--record DIR] [--interactive]\n");
	printPatternUsage(out);
	printBoardUsage(out);
}

bool parseDepths(const char *text, std::vector<double> &out)
{
	out.clear();
	std::string s(text);
	size_t pos = 0;
	while (pos <= s.size()) {
		size_t comma = s.find(',', pos);
		std::string item = s.substr(pos, comma == std::string::npos ? std::string::npos : comma - pos);
		char *end;
		double d = std::strtod(item.c_str(), &end);
		if (item.empty() || *end || !(d >= 0.3 && d <= 7.5))
			return false;
		out.push_back(d);
		if (comma == std::string::npos)
			break;
		pos = comma + 1;
	}
	return !out.empty();
}

// Returns 0, or 2 (usage error) after saying what is wrong.
int parseOptions(int argc, char **argv, Options &o)
{
	for (int i = 1; i < argc; i++) {
		std::string a = argv[i];
		auto value = [&]() -> const char * { return i + 1 < argc ? argv[++i] : nullptr; };
		const char *v = nullptr;
		bool ok = true;
		if (a == "--sim")
			o.sim = true;
		else if (a == "--no-depth-noise")
			o.depthNoise = false;
		else if (a == "--interactive")
			o.interactive = true;
		else if (a == "--live")
			o.live = true;
		else if (a == "-h" || a == "--help") {
			usage(stdout);
			std::exit(0);
		} else if (!(v = value()))
			ok = false;
		else if (a == "--seed")
			o.seed = std::strtoull(v, nullptr, 10);
		else if (a == "--sim-board-width")
			ok = (o.simBoardWidth = std::atoi(v)) == 0 || (o.simBoardWidth >= 16 && o.simBoardWidth <= 3840);
		else if (a == "--sim-colour-size")
			ok = parseSize(v, o.simColourWidth, o.simColourHeight, 1920, 1080);
		else if (a == "--sequence")
			o.sequence = v;
		else if (a == "--config")
			o.config = v;
		else if (a == "--view-timeout")
			ok = (o.viewTimeoutS = std::atof(v)) > 0;
		else if (a == "--step")
			ok = (o.step = std::atoi(v)) > 0;
		else if (a == "--output")
			o.output = v;
		else if (a == "--model") {
			MappingKind kind;
			ok = parseMappingKind(v, kind) && kind != MappingKind::Identity;
			o.model = kind;
		} else if (a == "--hold-out-every")
			ok = (o.holdOutEvery = std::atoi(v)) >= 2;
		else if (a == "--hold-out-depth")
			o.holdOutDepth = std::atof(v);
		else if (a == "--depths")
			ok = o.depthsGiven = parseDepths(v, o.depths);
		else if (a == "--grid")
			ok = std::sscanf(v, "%dx%d", &o.grid.cols, &o.grid.rows) == 2 &&
			     o.grid.cols >= 5 && o.grid.rows >= 5 && o.grid.cols != o.grid.rows && o.grid.cols * o.grid.rows <= 400;
		else if (a == "--max-rms")
			ok = (o.maxRmsPx = std::atof(v)) > 0;
		else if (a == "--preview")
			o.preview = v;
		else if (a == "--record")
			o.record = v;
		else {
			std::fprintf(stderr, "depthkey-calibrate: unknown option %s\n", a.c_str());
			usage(stderr);
			return 2;
		}
		if (!ok) {
			std::fprintf(stderr, "depthkey-calibrate: %s %s\n", a.c_str(),
				     v ? (std::string("has a bad value: ") + v).c_str() : "needs a value");
			return 2;
		}
	}
	if (int(o.sim) + int(!o.sequence.empty()) + int(o.live) != 1 || o.output.empty() ||
	    (!o.config.empty() && !o.live)) {
		std::fprintf(stderr, "depthkey-calibrate: give one of --sim, --sequence DIR, --live [--config FILE], "
				     "and --output FILE\n");
		usage(stderr);
		return 2;
	}
	return 0;
}

std::string utcNow()
{
	char buf[32];
	std::time_t now = std::time(nullptr);
	std::tm tm;
	gmtime_r(&now, &tm);
	std::strftime(buf, sizeof(buf), "%Y-%m-%dT%H:%M:%SZ", &tm);
	return buf;
}

// The detected circles drawn over both images, for the technician to check.
void writePreview(const std::string &dir, int index, const ColourFrame &colour, const DepthFrame &depth,
		  GridSize grid)
{
	::mkdir(dir.c_str(), 0755);
	char name[64];
	cv::Size size(grid.cols, grid.rows);

	std::vector<ImagePoint> centres;
	cv::Mat rgb(colour.rgb.height(), colour.rgb.width(), CV_8UC3, const_cast<Rgb8 *>(colour.rgb.data()));
	cv::Mat bgr;
	cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
	bool found = findColourGrid(colour.rgb, grid, centres) == 0;
	std::vector<cv::Point2f> points;
	for (const ImagePoint &p : centres)
		points.emplace_back(static_cast<float>(p.x), static_cast<float>(p.y));
	cv::drawChessboardCorners(bgr, size, points, found);
	std::snprintf(name, sizeof(name), "/view-%02d-colour.png", index);
	std::string error;
	if (writePicturePng(dir + name, bgr, error) < 0)
		std::printf("        preview not written: %s\n", error.c_str());

	Gray8Image scaled = amplitudeForDetection(depth.amplitude);
	cv::Mat gray(scaled.height(), scaled.width(), CV_8UC1, scaled.data()), tof;
	cv::cvtColor(gray, tof, cv::COLOR_GRAY2BGR);
	found = findAmplitudeGrid(depth.amplitude, grid, centres) == 0;
	points.clear();
	for (const ImagePoint &p : centres)
		points.emplace_back(static_cast<float>((p.x + 0.5) * kAmplitudeScale - 0.5),
				    static_cast<float>((p.y + 0.5) * kAmplitudeScale - 0.5));
	cv::drawChessboardCorners(tof, size, points, found);
	std::snprintf(name, sizeof(name), "/view-%02d-tof.png", index);
	if (writePicturePng(dir + name, tof, error) < 0)
		std::printf("        preview not written: %s\n", error.c_str());
}

void printReport(const CalibrationFit &fit)
{
	std::printf("\nresiduals in colour pixels (held out: %s)\n", fit.heldOutViews.c_str());
	std::printf("%-9s %-8s %8s %7s %8s %8s\n", "model", "set", "depth_m", "points", "rms_px", "max_px");
	for (size_t i = 0; i < fit.summaries.size(); i++) {
		const CalibrationSummary &s = fit.summaries[i];
		const char *name = mappingKindName(s.model);
		for (const CalibrationResidual &r : fit.residuals)
			if (r.model == s.model)
				std::printf("%-9s %-8s %8.2f %7d %8.3f %8.3f\n", name, r.heldOut ? "heldout" : "fit",
					    r.depthM, r.stats.points, r.stats.rmsPx, r.stats.maxPx);
		std::printf("%-9s %-8s %8s %7d %8.3f %8.3f\n", name, "fit", "all", s.fit.points, s.fit.rmsPx,
			    s.fit.maxPx);
		std::printf("%-9s %-8s %8s %7d %8.3f %8.3f\n", name, "heldout", "all", s.heldOut.points,
			    s.heldOut.rmsPx, s.heldOut.maxPx);
	}
}

// The views, from the simulator or a recorded sequence.
class ViewSource
{
public:
	int open(const Options &o, std::string &error)
	{
		options_ = &o;
		if (o.live)
			return live_.open({ o.config, o.grid, o.depths, o.depthsGiven, o.viewTimeoutS }, error);
		if (!o.sim)
			return openSequence(o.sequence, error);
		rig_.configure(o.simColourWidth, o.simColourHeight, true, 60);
		sim::PatternConditions conditions;
		conditions.seed = o.seed;
		conditions.depthNoise = o.depthNoise;
		sim::PatternBoard board;
		board.grid = o.grid;
		renderer_.configure(rig_, board, conditions);
		plan_ = calibrationPlan(o.depths);
		return 0;
	}
	size_t views() const
	{
		return options_->live  ? live_.views()
		       : options_->sim ? plan_.size()
				       : sequence_.colour().size() / options_->step;
	}
	const PatternStep *step(size_t i) const
	{
		return options_->live ? &live_.step(i) : options_->sim ? &plan_[i] : nullptr;
	}
	int read(size_t i, ColourFrame &colour, DepthFrame &depth, std::string &error)
	{
		if (options_->live)
			return live_.read(i, colour, depth, error);
		if (!options_->sim)
			return readSequence(i * options_->step, colour, depth, error);
		renderer_.render(renderer_.poseFor(plan_[i], static_cast<int>(i)), i, colour, depth);
		// View i is stamped i seconds, so that a recording of the views
		// pairs colour and depth frame by their one timestamp.
		colour.timestampNs = depth.timestampNs = i * 1000000000ull;
		return 0;
	}
	std::string colourName() const
	{
		if (options_->live)
			return live_.colourName();
		return options_->sim ? "sim colour " + std::to_string(options_->simColourWidth) + "x" +
					       std::to_string(options_->simColourHeight) + " seed " +
					       std::to_string(options_->seed)
				     : "sequence " + options_->sequence + " rgb";
	}
	std::string tofName() const
	{
		if (options_->live)
			return live_.tofName();
		return options_->sim ? "sim tof 160x124 seed " + std::to_string(options_->seed)
				     : "sequence " + options_->sequence + " depth+amplitude";
	}

private:
	// A recording (hal/recording/sequence_format.hpp) with amplitude: the
	// pattern is found in the ToF's amplitude image.
	int openSequence(const std::string &dir, std::string &error)
	{
		using namespace recording;
		if (int ret = sequence_.open(dir, { Rgb, Depth, Amplitude }); ret < 0) {
			error = sequence_.describeError();
			return ret;
		}
		if (sequence_.colour().empty() || sequence_.depth().empty()) {
			error = dir + ": rgb.txt and depth.txt must both list frames";
			return -EINVAL;
		}
		return 0;
	}
	// Colour frame i with the depth frame taken with it: the pattern is held
	// still, so the nearest in time shows it where the colour frame does.
	int readSequence(size_t i, ColourFrame &colour, DepthFrame &depth, std::string &error)
	{
		int ret = sequence_.readColour(i, colour);
		if (ret == 0)
			ret = sequence_.readDepth(sequence_.depthNearestColour(i), depth);
		if (ret < 0)
			error = sequence_.describeError();
		return ret;
	}

	const Options *options_ = nullptr;
	SequenceReader sequence_;
	CameraRig rig_;
	sim::PatternRenderer renderer_;
	std::vector<PatternStep> plan_;
	LiveViewSource live_;
};

} // namespace

int main(int argc, char **argv)
{
	// --board: the board calibration, a mode of its own.
	if (wantsBoardCalibration(argc, argv))
		return runBoardCalibration(argc, argv);
	// --print-pattern: the depth pattern as a PDF or SVG to print.
	if (wantsPatternPrint(argc, argv))
		return runPatternPrint(argc, argv);
	Options o;
	if (int ret = parseOptions(argc, argv, o); ret)
		return ret;

	std::string error;
	ViewSource source;
	if (source.open(o, error) < 0) {
		std::fprintf(stderr, "depthkey-calibrate: %s\n", error.c_str());
		return 1;
	}
	SequenceWriter recorder;
	if (!o.record.empty() && recorder.open(o.record) < 0) {
		std::fprintf(stderr, "depthkey-calibrate: %s\n", recorder.describeError().c_str());
		return 1;
	}

	std::printf("calibrating with a %dx%d grid of black circles, %zu views\n", o.grid.cols, o.grid.rows,
		    source.views());
	std::vector<CalibrationView> views;
	MappingModel sizes;
	ColourFrame colour;
	DepthFrame depth;
	for (size_t i = 0; i < source.views(); i++) {
		if (const PatternStep *step = source.step(i)) {
			std::printf("view %2zu/%zu: hold the pattern %.1f m from the camera, %s of the image\n",
				    i + 1, source.views(), step->depthM, step->where().c_str());
			std::fflush(stdout); // live: the technician reads it now
			if (o.interactive) {
				std::printf("        press Enter when it is there ");
				std::fflush(stdout);
				std::string line;
				std::getline(std::cin, line);
			}
		} else {
			std::printf("view %2zu/%zu: frame %zu of %s\n", i + 1, source.views(), i * o.step,
				    o.sequence.c_str());
		}
		if (source.read(i, colour, depth, error) < 0) {
			std::fprintf(stderr, "depthkey-calibrate: %s\n", error.c_str());
			return 1;
		}
		if (!o.record.empty() && (recorder.writeColour(colour) < 0 || recorder.writeDepth(depth) < 0)) {
			std::fprintf(stderr, "depthkey-calibrate: %s\n", recorder.describeError().c_str());
			return 1;
		}
		if (!o.preview.empty())
			writePreview(o.preview, static_cast<int>(i + 1), colour, depth, o.grid);

		CalibrationView view;
		if (pairView(colour, depth, o.grid, view, error) < 0) {
			std::printf("        rejected: %s\n", error.c_str());
			continue;
		}
		// The plan's depth groups the views; a sequence has only the
		// measured depth, grouped to 10 cm, and so has a live view held
		// elsewhere than the plan asked.
		double measured = view.depthM;
		const PatternStep *step = source.step(i);
		view.depthM = step && (!o.live || std::abs(measured - step->depthM) < 0.15)
				      ? step->depthM
				      : std::round(measured * 10.0) / 10.0;
		std::printf("        accepted: %d circles, pattern at %.2f m\n", o.grid.count(), measured);
		views.push_back(std::move(view));
		sizes.colourWidth = colour.rgb.width();
		sizes.colourHeight = colour.rgb.height();
		sizes.tofWidth = depth.depthMm.width();
		sizes.tofHeight = depth.depthMm.height();
	}

	CalibrationFitOptions fitOptions;
	fitOptions.sizes = sizes;
	fitOptions.holdOutEvery = o.holdOutEvery;
	fitOptions.holdOutDepthM = o.holdOutDepth;
	fitOptions.model = o.model;
	CalibrationFit fit;
	std::vector<std::string> notes;
	int ret = fitCalibration(views, fitOptions, fit, error, notes);
	for (const std::string &note : notes)
		std::printf("note: %s\n", note.c_str());
	if (ret < 0) {
		std::fprintf(stderr, "depthkey-calibrate: calibration failed with %zu accepted views: %s; %s left unchanged\n",
			     views.size(), error.c_str(), o.output.c_str());
		return 1;
	}
	printReport(fit);

	const CalibrationSummary *chosen = nullptr;
	for (const CalibrationSummary &s : fit.summaries)
		if (s.model == fit.mapping.kind)
			chosen = &s;
	const ResidualStats &judged = chosen->heldOut.points ? chosen->heldOut : chosen->fit;
	if (judged.rmsPx > o.maxRmsPx) {
		std::fprintf(stderr,
			     "depthkey-calibrate: calibration failed: model %s misses the held-out views by %.2f px RMS "
			     "(more than --max-rms %.2f); %s left unchanged\n",
			     mappingKindName(fit.mapping.kind), judged.rmsPx, o.maxRmsPx, o.output.c_str());
		return 1;
	}

	Calibration c;
	c.mapping = fit.mapping;
	c.date = utcNow();
	c.colourCamera = source.colourName();
	c.tofCamera = source.tofName();
	c.selectedBy = fit.selectedBy;
	c.heldOutViews = fit.heldOutViews;
	c.depthsM = fit.depthsM;
	c.summaries = fit.summaries;
	c.residuals = fit.residuals;
	// The simulated room is calibrated in one go: its board's display
	// shows the board pattern too, and its H goes in [board], which the
	// daemon uses while board.homography_file is empty (make run's
	// calibration, and the accuracy gate's, include the board).
	if (o.sim && o.simBoardWidth > 0) {
		BoardCalibration board;
		if (fitSimBoardCalibration(o.seed, sizes.colourWidth, sizes.colourHeight, o.simBoardWidth, board, error) < 0) {
			std::fprintf(stderr, "depthkey-calibrate: the simulated board: %s; %s left unchanged\n", error.c_str(),
				     o.output.c_str());
			return 1;
		}
		std::printf("board (the simulated display, %dx%d px): rms %.3f board px, max %.3f; kept in [board]\n",
			    board.boardWidth, board.boardHeight, board.rmsPx, board.maxPx);
		c.board = board;
	}
	if (writeCalibration(o.output, c, error) < 0) {
		std::fprintf(stderr, "depthkey-calibrate: %s; %s left unchanged\n", error.c_str(), o.output.c_str());
		return 1;
	}
	std::printf("\nselected model %s (%s), wrote %s\n", mappingKindName(fit.mapping.kind),
		    fit.selectedBy == "option" ? "--model" : "lowest held-out error", o.output.c_str());
	std::printf("summary model=%s rms_px=%.2f max_px=%.2f heldout_rms_px=%.2f\n",
		    mappingKindName(fit.mapping.kind), chosen->fit.rmsPx, chosen->fit.maxPx, chosen->heldOut.rmsPx);
	return 0;
}
