#include "daemon/device_factory.hpp"

#include "hal/shm_frame_sink.hpp"
#include "hal/sim/sim_cameras.hpp"

namespace depthkey {

// The config loader only accepts backends listed here, so the fallbacks below
// are never reached with a validated config.
std::unique_ptr<ColourCamera> createColourCamera(const Settings &settings)
{
	return std::make_unique<SimColourCamera>(settings.colour, settings.sim);
}

std::unique_ptr<DepthCamera> createDepthCamera(const Settings &settings)
{
	return std::make_unique<SimDepthCamera>(settings.depth, settings.sim);
}

std::unique_ptr<FrameSink> createFrameSink(const Settings &)
{
	return std::make_unique<ShmFrameSink>();
}

std::unique_ptr<StatusLeds> createStatusLeds(const Settings &)
{
	return std::make_unique<NoStatusLeds>();
}

} // namespace depthkey
