// Simulated colour and depth cameras: timer-driven renderers of a scene,
// free-running at their own frame rates like the real pair.
#pragma once

#include "config/settings.hpp"
#include "hal/camera.hpp"
#include "hal/sim/simple_scene.hpp"

namespace depthkey {

class SimColourCamera : public ColourCamera
{
public:
	SimColourCamera(const ColourCameraSettings &settings, const SimSettings &sim);
	std::string name() const override { return "sim-colour"; }
	int start(EventLoop &loop, FrameHandler onFrame, StatusHandler onStatus) override;
	void stop() override;
	DeviceStatus status() const override { return status_; }

private:
	void capture();

	ColourCameraSettings settings_;
	SimpleScene scene_;
	EventLoop *loop_ = nullptr;
	EventSource timer_;
	FrameHandler onFrame_;
	ColourFrame frame_;
	DeviceStatus status_;
	uint64_t startUs_ = 0;
};

class SimDepthCamera : public DepthCamera
{
public:
	SimDepthCamera(const DepthCameraSettings &settings, const SimSettings &sim);
	std::string name() const override { return "sim-depth"; }
	int start(EventLoop &loop, FrameHandler onFrame, StatusHandler onStatus) override;
	void stop() override;
	DeviceStatus status() const override { return status_; }

	static constexpr int kWidth = 160;  // the SR-2's sensor
	static constexpr int kHeight = 124;

private:
	void capture();

	DepthCameraSettings settings_;
	SimpleScene scene_;
	EventLoop *loop_ = nullptr;
	EventSource timer_;
	FrameHandler onFrame_;
	DepthFrame frame_;
	DeviceStatus status_;
	uint64_t startUs_ = 0;
};

} // namespace depthkey
