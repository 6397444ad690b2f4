#include "daemon/device_factory.hpp"

#include "daemon/log.hpp"
#include "hal/board/board_sources.hpp"
#include "hal/gpio/gpiod_status_leds.hpp"
#include "hal/replay/replay_cameras.hpp"
#include "hal/shm_frame_sink.hpp"
#include "hal/sim/sim_cameras.hpp"
#include "hal/sr2/sr2_camera.hpp"
#include "hal/v4l2/v4l2_cameras.hpp"

namespace depthkey {

namespace {

// The replay colour and depth cameras of one folder must share a timeline
// (to keep the recorded order). The daemon creates them one after the
// other; the second finds the first's timeline here while it lives. Colour
// frames play only at [colour]'s size: the outputs are made for it.
std::shared_ptr<ReplayTimeline> replayTimeline(const Settings &settings)
{
	static std::weak_ptr<ReplayTimeline> current;
	std::shared_ptr<ReplayTimeline> timeline = current.lock();
	const int width = settings.colour.width, height = settings.colour.height;
	if (!timeline || !timeline->plays(settings.replay, width, height)) {
		timeline = std::make_shared<ReplayTimeline>(settings.replay, width, height);
		current = timeline;
	}
	return timeline;
}

} // namespace

// The config loader only accepts backends listed here, so the fallbacks below
// are never reached with a validated config.
std::unique_ptr<ColourCamera> createColourCamera(const Settings &settings)
{
	if (settings.colour.backend == "v4l2")
		return std::make_unique<V4l2ColourCamera>(settings.colour);
	if (settings.colour.backend == "replay")
		return std::make_unique<ReplayColourCamera>(replayTimeline(settings));
	return std::make_unique<SimColourCamera>(settings.colour, settings.sim);
}

std::unique_ptr<DepthCamera> createDepthCamera(const Settings &settings)
{
	if (settings.depth.backend == "sr2")
		return std::make_unique<Sr2Camera>(settings.depth);
	if (settings.depth.backend == "v4l2")
		return std::make_unique<V4l2DepthCamera>(settings.depth);
	if (settings.depth.backend == "replay")
		return std::make_unique<ReplayDepthCamera>(replayTimeline(settings));
	return std::make_unique<SimDepthCamera>(settings.depth, settings.sim);
}

std::unique_ptr<FrameSink> createFrameSink(const Settings &)
{
	return std::make_unique<ShmFrameSink>();
}

std::unique_ptr<StatusLeds> createStatusLeds(const Settings &settings)
{
	if (settings.leds.backend == "gpiod")
		return std::make_unique<GpiodStatusLeds>(
			[](const std::string &led, int error, const std::string &detail) {
				// Once per line: the LED stays dark, the daemon goes on,
				// and the backend says when it lights again (error 0).
				std::string device = led.empty() ? "leds" : "led-" + led;
				if (error == 0)
					logger().clearError(device, "status LED back: " + detail, { { "DEVICE", device } });
				else
					logger().errorOnce(device, "status LED unavailable: " + detail,
							   { { "DEVICE", device }, { "ERROR", errnoText(error) } });
			});
	return std::make_unique<NoStatusLeds>();
}

std::unique_ptr<ColourCamera> createBoardSourceFor(const Settings &settings)
{
	return createBoardSource(settings);
}

} // namespace depthkey
