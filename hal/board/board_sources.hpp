// Where the board's own picture comes from (board.backend). A board source
// is a colour camera as far as the daemon is concerned (hal/camera.hpp): it
// is started on the event loop, delivers pictures through a callback and
// reports its state, Lost while it has nothing new to give (the daemon keeps
// the last good picture).
//   colour  one solid picture of board.width x board.height, at start
//   image   a PNG/JPEG file, read again on change (hal/board/image_board_source.hpp)
//   v4l2    a capture stick: V4l2ColourCamera with the board's settings,
//           its reconnect loop included ("v4l2-board")
//   sim     the simulated board's display (hal/sim/board_display.hpp) at
//           board.fps, on the sim cameras' clock
#pragma once

#include "hal/camera.hpp"
#include "hal/sim/board_display.hpp"
#include "hal/sim/sim_cameras.hpp"
#include "settings/settings.hpp"

#include <memory>

namespace depthkey {

using BoardSource = ColourCamera;

class ColourBoardSource : public BoardSource
{
public:
	explicit ColourBoardSource(const BoardSettings &settings) : settings_(settings) {}
	std::string name() const override { return "board-colour"; }
	int start(EventLoop &loop, FrameHandler onFrame, StatusHandler onStatus) override;
	void stop() override { status_ = {}; }
	DeviceStatus status() const override { return status_; }

private:
	BoardSettings settings_;
	DeviceStatus status_;
};

class SimBoardSource final : public PeriodicSimCamera<ColourFrame>
{
public:
	SimBoardSource(const BoardSettings &settings, const SimSettings &sim) : settings_(settings), sim_(sim) {}
	~SimBoardSource() override { stop(); }
	std::string name() const override { return "sim-board"; }

private:
	const char *threadName() const override { return "dk-sim-board"; }
	int fps() const override { return settings_.fps; }
	void prepare() override { display_.configure(sim_, settings_.width); }
	void render(uint64_t nowUs, ColourFrame &frame) override { display_.render(nowUs / 1e6, frame.rgb); }

	BoardSettings settings_;
	SimSettings sim_;
	SimBoardDisplay display_;
};

// The colour camera settings a capture stick is opened with.
ColourCameraSettings captureStickSettings(const BoardSettings &board);

std::unique_ptr<BoardSource> createBoardSource(const Settings &settings);

} // namespace depthkey
