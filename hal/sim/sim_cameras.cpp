#include "hal/sim/sim_cameras.hpp"

namespace depthkey {

SimColourCamera::SimColourCamera(const ColourCameraSettings &settings, const SimSettings &sim)
	: settings_(settings), scene_(sim.seed)
{
}

int SimColourCamera::start(EventLoop &loop, FrameHandler onFrame, StatusHandler onStatus)
{
	loop_ = &loop;
	onFrame_ = std::move(onFrame);
	frame_.rgb.resize(settings_.width, settings_.height);
	frame_.sequence = 0;
	startUs_ = loop.nowUs();
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
	scene_.renderColour((now - startUs_) / 1e6, frame_.rgb);
	frame_.timestampNs = now * 1000u;
	frame_.sequence++;
	onFrame_(frame_);
}

SimDepthCamera::SimDepthCamera(const DepthCameraSettings &settings, const SimSettings &sim)
	: settings_(settings), scene_(sim.seed)
{
}

int SimDepthCamera::start(EventLoop &loop, FrameHandler onFrame, StatusHandler onStatus)
{
	loop_ = &loop;
	onFrame_ = std::move(onFrame);
	frame_.depthMm.resize(kWidth, kHeight);
	frame_.amplitude.resize(kWidth, kHeight);
	frame_.intensity.resize(kWidth, kHeight);
	frame_.sequence = 0;
	startUs_ = loop.nowUs();
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
	scene_.renderDepth((now - startUs_) / 1e6, frame_);
	frame_.timestampNs = now * 1000u;
	frame_.sequence++;
	onFrame_(frame_);
}

} // namespace depthkey
