// depthkey-calibrate --live: the views of the pattern taken from the
// configured cameras, opened through hal/ as depthkeyd opens them (the daemon
// must be stopped: it holds the devices). For each step of the plan the tool
// says where to hold the pattern; a view is taken when both cameras see the
// whole grid and it has been still for 0.5 s (circle centres moving less
// than 1 colour px and 0.5 ToF px). The pattern is searched for off the
// loop that reads the cameras (background_grid_search.hpp), so the view's
// timeout comes on time whatever the frames show. On the simulated cameras a simulated
// technician (hal/sim/sim_technician.hpp) carries the pattern where the
// tool says.
#pragma once

#include "algo/calibration_plan.hpp"
#include "algo/circle_grid_detector.hpp"
#include "algo/frames.hpp"
#include "hal/camera.hpp"
#include "hal/event_loop.hpp"
#include "hal/sim/sim_technician.hpp"
#include "settings/settings.hpp"
#include "tools/calibrate_live/background_grid_search.hpp"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace depthkey {

struct LiveOptions {
	std::string configPath;      // "" = the daemon's default config
	GridSize grid;
	std::vector<double> depths;
	bool depthsGiven = false;    // --depths: asked for as they are, even behind the board
	double viewTimeoutS = 60;    // a view not taken by then is given up (rejected)
};

class LiveViewSource
{
public:
	~LiveViewSource() { close(); }

	// Reads the config and starts both cameras. Returns 0 or a negative
	// errno with error saying why.
	int open(const LiveOptions &options, std::string &error);
	void close();

	size_t views() const { return plan_.size(); }
	const PatternStep &step(size_t i) const { return plan_[i]; }
	// Waits for view i: both cameras see the whole grid, still for 0.5 s.
	// 0 with the frames; on the timeout 0 with the last frames (the caller
	// then says which camera did not see the grid); -ENODATA when a camera
	// delivered nothing at all.
	int read(size_t i, ColourFrame &colour, DepthFrame &depth, std::string &error);
	std::string colourName() const { return colourName_; }
	std::string tofName() const { return tofName_; }

private:
	// A grid's centres held still since sinceNs (or not seen: sinceNs 0).
	struct Stillness {
		std::vector<ImagePoint> reference, centres;
		uint64_t sinceNs = 0, lastNs = 0;
		bool seen = false;
		void update(bool found, uint64_t timeNs, double limitPx);
		double stillS() const { return seen ? (lastNs - sinceNs) / 1e9 : 0; }
	};
	// Says once, and again when it changes, why a camera does not see the grid.
	struct MissReport {
		const char *camera;
		std::string lastReason;
		uint64_t nextUs = 0;
		void report(uint64_t startUs, uint64_t nowUs, const std::function<GridMiss()> &explain);
	};
	void onStatus(const char *role, const std::string &name, const DeviceStatus &status);
	// The default plan without the depths the pattern cannot be held at in
	// this room (behind the board), from the first depth frame; said once.
	void fitPlanToTheRoom();

	LiveOptions options_;
	Settings settings_;
	EventLoop loop_;
	std::unique_ptr<ColourCamera> colour_;
	std::unique_ptr<DepthCamera> depth_;
	std::shared_ptr<sim::SimTechnician> technician_; // simulated cameras only
	std::vector<PatternStep> plan_;
	std::string colourName_, tofName_;
	ColourFrame lastColour_;
	DepthFrame lastDepth_;
	bool newColour_ = false, newDepth_ = false;
	bool haveColour_ = false, haveDepth_ = false;
	// Declared after the frames: a search still running at the end is
	// waited for first.
	BackgroundGridSearch colourSearch_, tofSearch_;
};

} // namespace depthkey
