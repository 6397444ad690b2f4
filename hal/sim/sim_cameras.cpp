#include "hal/sim/sim_cameras.hpp"

namespace depthkey {

SimColourCamera::SimColourCamera(const ColourCameraSettings &settings, const SimSettings &sim)
	: settings_(settings), sim_(sim)
{
}

int SimColourCamera::start(EventLoop &loop, FrameHandler onFrame, StatusHandler onStatus)
{
	loop_ = &loop;
	onFrame_ = std::move(onFrame);
	simulator_.configure(sim_, settings_.width, settings_.height);
	frame_.sequence = 0;
	int ret = loop.addPeriodic(1000000u / settings_.fps, [this] { capture(); }, timer_);
	if (ret < 0)
		return ret;
	status_ = { DeviceState::Streaming, 0, "" };
	onStatus(status_);
	return 0;
}

void SimColourCamera::stop()
{
	timer_.reset();
	status_ = { DeviceState::Stopped, 0, "" };
}

void SimColourCamera::capture()
{
	uint64_t now = loop_->nowUs();
	simulator_.renderColour(now / 1e6, frame_);
	frame_.timestampNs = now * 1000u;
	frame_.sequence++;
	onFrame_(frame_);
}

SimDepthCamera::SimDepthCamera(const DepthCameraSettings &settings, const SimSettings &sim)
	: settings_(settings), sim_(sim)
{
}

int SimDepthCamera::start(EventLoop &loop, FrameHandler onFrame, StatusHandler onStatus)
{
	loop_ = &loop;
	onFrame_ = std::move(onFrame);
	// The colour size does not matter for the depth view.
	simulator_.configure(sim_, 640, 480);
	timing_.configure(sim_, 25, settings_.fps);
	frame_.sequence = 0;
	int ret = loop.addPeriodic(1000000u / settings_.fps, [this] { capture(); }, timer_);
	if (ret < 0)
		return ret;
	status_ = { DeviceState::Streaming, 0, "" };
	onStatus(status_);
	return 0;
}

void SimDepthCamera::stop()
{
	timer_.reset();
	status_ = { DeviceState::Stopped, 0, "" };
}

void SimDepthCamera::capture()
{
	uint64_t now = loop_->nowUs();
	// The frame shows the scene latency (and jitter) before it arrives.
	double shown = now / 1e6 - sim_.depthLatencyMs / 1000.0 -
		       sim_.depthJitterMs / 1000.0 * timing_.jitterUnit(2, frame_.sequence);
	simulator_.renderDepth(shown, frame_);
	frame_.timestampNs = now * 1000u;
	frame_.sequence++;
	onFrame_(frame_);
}

} // namespace depthkey
