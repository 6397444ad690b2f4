#include "tools/calibrate_live/live_view_source.hpp"

#include <algorithm>

#include "config/config_loader.hpp"
#include "daemon/device_factory.hpp"
#include "hal/sim/lecture_simulator.hpp"
#include "hal/sim/sim_cameras.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <systemd/sd-event.h>

namespace depthkey {

namespace {

constexpr double kStillS = 0.5;
constexpr double kColourStillPx = 1.0;
constexpr double kTofStillPx = 0.5;
// A camera that has not seen the whole grid this long into a view says why
// (issue 30: within 2 s, not at the timeout), and again when the reason
// changes; the reason is looked at no more often than kExplainEveryUs.
constexpr uint64_t kExplainAfterUs = 1'500'000;
constexpr uint64_t kExplainEveryUs = 500'000;

double largestMove(const std::vector<ImagePoint> &a, const std::vector<ImagePoint> &b)
{
	double worst = 0;
	for (size_t i = 0; i < a.size() && i < b.size(); i++)
		worst = std::max(worst, std::hypot(a[i].x - b[i].x, a[i].y - b[i].y));
	return worst;
}

} // namespace

void LiveViewSource::Stillness::update(bool found, uint64_t timeNs, double limitPx)
{
	if (!found) {
		seen = false;
		return;
	}
	if (!seen || reference.size() != centres.size() || largestMove(reference, centres) > limitPx) {
		reference = centres;
		sinceNs = timeNs;
	}
	seen = true;
	lastNs = timeNs;
}

int LiveViewSource::open(const LiveOptions &options, std::string &error)
{
	options_ = options;
	const std::string path = options.configPath.empty() ? findDefaultConfig() : options.configPath;
	ConfigResult config = loadConfig(path);
	if (!config.ok()) {
		error = config.errors.front().toString();
		return -EINVAL;
	}
	settings_ = config.settings;
	plan_ = calibrationPlan(options.depths);
	int ret = loop_.open();
	if (ret < 0) {
		error = "cannot create the event loop";
		return ret;
	}

	// The cameras as depthkeyd makes them; the simulated ones with a
	// technician who holds the pattern where the plan says.
	if (settings_.colour.backend == "sim" || settings_.depth.backend == "sim") {
		LectureSimulator scene;
		scene.configure(settings_.sim, settings_.colour.width, settings_.colour.height);
		sim::PatternBoard board;
		board.grid = options.grid;
		technician_ = std::make_shared<sim::SimTechnician>();
		technician_->configure(scene.rig(), board);
	}
	if (settings_.colour.backend == "sim") {
		auto camera = std::make_unique<SimColourCamera>(settings_.colour, settings_.sim);
		camera->setTechnician(technician_);
		colour_ = std::move(camera);
	} else {
		colour_ = createColourCamera(settings_);
	}
	if (settings_.depth.backend == "sim") {
		auto camera = std::make_unique<SimDepthCamera>(settings_.depth, settings_.sim);
		camera->setTechnician(technician_);
		depth_ = std::move(camera);
	} else {
		depth_ = createDepthCamera(settings_);
	}
	colourName_ = colour_->name() + (settings_.colour.backend == "sim" ? " seed " + std::to_string(settings_.sim.seed)
									 : " " + settings_.colour.device) +
		      " " + std::to_string(settings_.colour.width) + "x" + std::to_string(settings_.colour.height);
	tofName_ = depth_->name() + (settings_.depth.backend == "sim" ? " seed " + std::to_string(settings_.sim.seed)
								     : settings_.depth.backend == "v4l2" ? " " + settings_.depth.device
													     : "");

	auto onColour = [this](const ColourFrame &frame) {
		lastColour_ = frame; // same size each time: no allocation after the first
		newColour_ = haveColour_ = true;
	};
	auto onDepth = [this](const DepthFrame &frame) {
		lastDepth_ = frame;
		newDepth_ = haveDepth_ = true;
	};
	std::string colourName = colour_->name(), depthName = depth_->name();
	if ((ret = colour_->start(loop_, onColour, [this, colourName](const DeviceStatus &s) {
		     onStatus("colour", colourName, s);
	     })) < 0 ||
	    (ret = depth_->start(loop_, onDepth, [this, depthName](const DeviceStatus &s) {
		     onStatus("depth", depthName, s);
	     })) < 0) {
		error = "cannot start the cameras: check [colour] and [depth] in " + path;
		return ret;
	}
	if (!options.depthsGiven)
		fitPlanToTheRoom();
	return 0;
}

void LiveViewSource::fitPlanToTheRoom()
{
	// A pattern held 25 cm before the board still shows a clear step in depth.
	constexpr double kClearanceM = 0.25;
	constexpr uint64_t kWaitUs = 3'000'000;
	const uint64_t deadlineUs = loop_.nowUs() + kWaitUs;
	while (!haveDepth_ && loop_.nowUs() < deadlineUs)
		if (sd_event_run(loop_.handle(), 10'000) < 0)
			return;
	const int farMm = haveDepth_ ? farSurfaceMm(lastDepth_.depthMm) : 0;
	if (farMm == 0)
		return; // nothing measured: the whole plan, as asked
	const std::vector<double> kept = depthsInFrontOf(options_.depths, farMm / 1000.0, kClearanceM);
	if (kept.size() == options_.depths.size())
		return;
	std::string left;
	for (double depth : options_.depths)
		if (std::find(kept.begin(), kept.end(), depth) == kept.end()) {
			char text[32];
			std::snprintf(text, sizeof(text), "%s%.1f", left.empty() ? "" : ", ", depth);
			left += text;
		}
	if (kept.empty()) {
		std::printf("        the room's far surface is %.2f m from the depth camera, nearer than every view "
			    "of the plan: give --depths nearer than %.2f m\n",
			    farMm / 1000.0, farMm / 1000.0 - kClearanceM);
		std::fflush(stdout);
		return;
	}
	std::printf("        the room's far surface (the board?) is %.2f m from the depth camera: the views at %s m "
		    "would be behind it or against it, left out (--depths asks for any depths)\n",
		    farMm / 1000.0, left.c_str());
	std::fflush(stdout);
	options_.depths = kept;
	plan_ = calibrationPlan(kept);
}

void LiveViewSource::close()
{
	if (colour_)
		colour_->stop();
	if (depth_)
		depth_->stop();
	colour_.reset();
	depth_.reset();
}

void LiveViewSource::onStatus(const char *role, const std::string &name, const DeviceStatus &status)
{
	if (status.state == DeviceState::Lost)
		std::printf("        %s camera %s lost: %s (is depthkeyd running? it holds the cameras: "
			    "systemctl stop depthkeyd)\n",
			    role, name.c_str(), status.detail.c_str());
	else if (status.state == DeviceState::Streaming)
		std::printf("        %s camera %s streaming\n", role, name.c_str());
	std::fflush(stdout);
}

void LiveViewSource::MissReport::report(uint64_t startUs, uint64_t nowUs, const std::function<GridMiss()> &explain)
{
	if (nowUs < nextUs)
		return;
	nextUs = nowUs + kExplainEveryUs;
	GridMiss miss = explain();
	if (miss.reason() == lastReason)
		return;
	lastReason = miss.reason();
	std::printf("        %s camera, %.1f s into the view: %s\n", camera, (nowUs - startUs) / 1e6,
		    miss.describe().c_str());
	std::fflush(stdout);
}

int LiveViewSource::read(size_t i, ColourFrame &colour, DepthFrame &depth, std::string &error)
{
	const uint64_t startUs = loop_.nowUs();
	if (technician_)
		technician_->holdAt(plan_[i], static_cast<int>(i), startUs / 1e6);
	const uint64_t deadlineUs = startUs + static_cast<uint64_t>(options_.viewTimeoutS * 1e6);
	Stillness colourGrid, tofGrid;
	ColourFrame searchedColour;
	DepthFrame searchedDepth;
	MissReport colourMiss{ "colour", {}, 0 }, tofMiss{ "depth (amplitude)", {}, 0 };
	while (loop_.nowUs() < deadlineUs) {
		// Short waits: a search's end is seen within 10 ms.
		int ret = sd_event_run(loop_.handle(), 10'000);
		if (ret < 0) {
			error = "event loop failed";
			return ret;
		}
		// A frame that came while the technician was told to move on is
		// not this view's: only frames after the instruction count (a
		// search of an earlier view's frame still running is one).
		const GridSize grid = options_.grid;
		if (newColour_ && !colourSearch_.busy()) {
			newColour_ = false;
			colourSearch_.start([grid, rgb = lastColour_.rgb](std::vector<ImagePoint> &centres) {
				return findColourGrid(rgb, grid, centres);
			}, lastColour_.timestampNs);
			searchedColour = lastColour_;
		}
		if (newDepth_ && !tofSearch_.busy()) {
			newDepth_ = false;
			tofSearch_.start([grid, amplitude = lastDepth_.amplitude](std::vector<ImagePoint> &centres) {
				return findAmplitudeGrid(amplitude, grid, centres);
			}, lastDepth_.timestampNs);
			searchedDepth = lastDepth_;
		}
		bool found;
		uint64_t timeNs;
		if (colourSearch_.done(found, colourGrid.centres, timeNs))
			colourGrid.update(found && timeNs >= startUs * 1000u, timeNs, kColourStillPx);
		if (tofSearch_.done(found, tofGrid.centres, timeNs))
			tofGrid.update(found && timeNs >= startUs * 1000u, timeNs, kTofStillPx); // ToF pixels
		uint64_t nowUs = loop_.nowUs();
		// Explained from a frame taken kExplainAfterUs after the instruction
		// or later, when the pattern has had time to settle: on a loaded box
		// the last frame can be one taken while it still moved (CI, 8
		// December: "35 of 35 circles found, but not as a grid" 1.5 s into a
		// view the desk half hides, from a frame taken mid-move).
		const uint64_t settledNs = (startUs + kExplainAfterUs) * 1000u;
		if (nowUs >= startUs + kExplainAfterUs) {
			if (!colourGrid.seen && haveColour_ && lastColour_.timestampNs >= settledNs)
				colourMiss.report(startUs, nowUs, [&] { return explainColourMiss(lastColour_.rgb, options_.grid); });
			if (!tofGrid.seen && haveDepth_ && lastDepth_.timestampNs >= settledNs)
				tofMiss.report(startUs, nowUs, [&] { return explainAmplitudeMiss(lastDepth_.amplitude, options_.grid); });
		}
		if (colourGrid.stillS() >= kStillS && tofGrid.stillS() >= kStillS) {
			// The frames whose grids were still: the last searched.
			colour = searchedColour;
			depth = searchedDepth;
			return 0;
		}
	}
	if (!haveColour_ || !haveDepth_) {
		error = std::string("no frame from the ") + (!haveColour_ ? "colour" : "depth") + " camera in " +
			std::to_string(static_cast<int>(options_.viewTimeoutS)) + " s";
		return -ENODATA;
	}
	std::printf("        not still in both cameras within %.0f s (colour %s, depth %s)\n", options_.viewTimeoutS,
		    colourGrid.seen ? "sees the grid" : "does not see the grid",
		    tofGrid.seen ? "sees the grid" : "does not see the grid");
	colour = lastColour_;
	depth = lastDepth_;
	return 0;
}

} // namespace depthkey
