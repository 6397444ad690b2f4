// Simulated colour and depth cameras: timer-driven views of the simulated
// lecture (hal/sim/lecture_simulator.hpp), free-running at their own frame
// rates like the real pair. Scene time is CLOCK_MONOTONIC, shared by both,
// so the two views agree. The depth camera stamps each frame latency +
// jitter after the moment it shows, as a real ToF delivers it late.
#pragma once

#include "config/settings.hpp"
#include "hal/camera.hpp"
#include "hal/sim/lecture_simulator.hpp"
#include "hal/sim/sim_timing.hpp"

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
	SimSettings sim_;
	LectureSimulator simulator_;
	EventLoop *loop_ = nullptr;
	EventSource timer_;
	FrameHandler onFrame_;
	ColourFrame frame_;
	DeviceStatus status_;
};

class SimDepthCamera : public DepthCamera
{
public:
	SimDepthCamera(const DepthCameraSettings &settings, const SimSettings &sim);
	std::string name() const override { return "sim-depth"; }
	int start(EventLoop &loop, FrameHandler onFrame, StatusHandler onStatus) override;
	void stop() override;
	DeviceStatus status() const override { return status_; }

	static constexpr int kWidth = LectureSimulator::kTofWidth;  // the SR-2's sensor
	static constexpr int kHeight = LectureSimulator::kTofHeight;

private:
	void capture();

	DepthCameraSettings settings_;
	SimSettings sim_;
	LectureSimulator simulator_;
	sim::SimTiming timing_;
	EventLoop *loop_ = nullptr;
	EventSource timer_;
	FrameHandler onFrame_;
	DepthFrame frame_;
	DeviceStatus status_;
};

} // namespace depthkey
