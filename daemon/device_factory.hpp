// Chooses each device's backend from the config. The rest of the daemon only
// sees the hal/ interfaces and never knows whether a camera is real.
#pragma once

#include "hal/camera.hpp"
#include "hal/frame_sink.hpp"
#include "hal/status_leds.hpp"
#include "settings/settings.hpp"

#include <functional>
#include <memory>

namespace depthkey {

std::unique_ptr<ColourCamera> createColourCamera(const Settings &settings);
std::unique_ptr<DepthCamera> createDepthCamera(const Settings &settings);
std::unique_ptr<FrameSink> createFrameSink(const Settings &settings);
std::unique_ptr<StatusLeds> createStatusLeds(const Settings &settings);
// board.backend (hal/board/board_sources.hpp).
std::unique_ptr<ColourCamera> createBoardSourceFor(const Settings &settings);

// What the daemon calls to get its devices: the backends above by default,
// fakes in tests of the daemon's own behaviour (offline frames, recovery).
struct DeviceFactory {
	std::function<std::unique_ptr<ColourCamera>(const Settings &)> colourCamera = createColourCamera;
	std::function<std::unique_ptr<DepthCamera>(const Settings &)> depthCamera = createDepthCamera;
	std::function<std::unique_ptr<FrameSink>(const Settings &)> frameSink = createFrameSink;
	std::function<std::unique_ptr<StatusLeds>(const Settings &)> statusLeds = createStatusLeds;
	std::function<std::unique_ptr<ColourCamera>(const Settings &)> boardSource = createBoardSourceFor;
	// Tests only: runs on the keying worker before each frame is keyed (a
	// slow box, a frame being keyed when the daemon stops). Empty by default.
	std::function<void()> beforeKeying;
};

} // namespace depthkey
