// Chooses each device's backend from the config. The rest of the daemon only
// sees the hal/ interfaces and never knows whether a camera is real.
#pragma once

#include "config/settings.hpp"
#include "hal/camera.hpp"
#include "hal/frame_sink.hpp"
#include "hal/status_leds.hpp"

#include <memory>

namespace depthkey {

std::unique_ptr<ColourCamera> createColourCamera(const Settings &settings);
std::unique_ptr<DepthCamera> createDepthCamera(const Settings &settings);
std::unique_ptr<FrameSink> createFrameSink(const Settings &settings);
std::unique_ptr<StatusLeds> createStatusLeds(const Settings &settings);

} // namespace depthkey
