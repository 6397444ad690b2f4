// Simulated colour and depth cameras: timer-driven views of the simulated
// lecture (hal/sim/lecture_simulator.hpp), free-running at their own frame
// rates like the real pair. Scene time is CLOCK_MONOTONIC, shared by both,
// so the two views agree. The depth camera stamps each frame latency +
// jitter after the moment it shows, as a real ToF delivers it late. The
// colour camera's capture instants jitter around its period
// (sim.colour_jitter_ms): each frame shows the scene at its jittered
// capture instant and carries that instant as its timestamp, as a real
// camera's frames do; jittering the delivery alone would leave the
// timestamps (what the daemon pairs and measures by) on the period.
#pragma once

#include "hal/camera.hpp"
#include "hal/sim/lecture_simulator.hpp"
#include "hal/sim/sim_technician.hpp"
#include "hal/sim/sim_timing.hpp"
#include "settings/settings.hpp"

#include <algorithm>
#include <memory>

namespace depthkey {

// What both simulated cameras share: a periodic timer on the event loop that
// renders a frame into a reused buffer, stamps it and hands it over.
template<typename Frame>
class PeriodicSimCamera : public Camera<Frame>
{
public:
	using typename Camera<Frame>::FrameHandler;
	using typename Camera<Frame>::StatusHandler;

	using typename Camera<Frame>::FrameLender;

	void lendFrames(FrameLender lender) override { lender_ = std::move(lender); }

	int start(EventLoop &loop, FrameHandler onFrame, StatusHandler onStatus) override
	{
		loop_ = &loop;
		onFrame_ = std::move(onFrame);
		prepare();
		sequence_ = 0;
		int ret = loop.addPeriodic(1000000u / fps(), [this] { capture(); }, timer_);
		if (ret < 0)
			return ret;
		status_ = { DeviceState::Streaming, 0, "" };
		onStatus(status_);
		return 0;
	}
	void stop() override
	{
		timer_.reset();
		status_ = { DeviceState::Stopped, 0, "" };
	}
	DeviceStatus status() const override { return status_; }

protected:
	virtual int fps() const = 0;
	virtual void prepare() = 0;
	// Renders the scene for capture time nowUs; frame.sequence is the
	// previous frame's number.
	virtual void render(uint64_t nowUs, Frame &frame) = 0;
	// How long before its delivery (the timer's tick) frame n (from 0) was
	// captured: its timestamp and the scene it shows.
	virtual uint64_t captureDelayUs(uint64_t /*n*/) const { return 0; }

private:
	void capture()
	{
		uint64_t now = loop_->nowUs();
		now -= std::min(now, captureDelayUs(sequence_));
		Frame *lent = lender_ ? lender_() : nullptr;
		Frame &frame = lent ? *lent : frame_; // frame_ stays empty while frames are lent
		frame.sequence = sequence_;
		render(now, frame);
		frame.timestampNs = now * 1000u;
		frame.sequence = ++sequence_;
		onFrame_(frame);
	}

	EventLoop *loop_ = nullptr;
	EventSource timer_;
	FrameHandler onFrame_;
	FrameLender lender_;
	Frame frame_;
	uint64_t sequence_ = 0; // the last frame's number, whichever buffer it was made in
	DeviceStatus status_;
};

class SimColourCamera : public PeriodicSimCamera<ColourFrame>
{
public:
	SimColourCamera(const ColourCameraSettings &settings, const SimSettings &sim)
		: settings_(settings), sim_(sim) {}
	std::string name() const override { return "sim-colour"; }
	// A calibration session (depthkey-calibrate --live): the technician's
	// pattern instead of the lecture. Shared with the depth camera.
	void setTechnician(std::shared_ptr<const sim::SimTechnician> technician) { technician_ = std::move(technician); }

private:
	int fps() const override { return settings_.fps; }
	void prepare() override;
	void render(uint64_t nowUs, ColourFrame &frame) override;
	uint64_t captureDelayUs(uint64_t n) const override;

	ColourCameraSettings settings_;
	SimSettings sim_;
	LectureSimulator simulator_;
	sim::SimTiming timing_;
	GroundTruth truth_; // reused; its alpha is copied into each frame (same size: no allocation)
	std::shared_ptr<const sim::SimTechnician> technician_;
};

class SimDepthCamera : public PeriodicSimCamera<DepthFrame>
{
public:
	SimDepthCamera(const DepthCameraSettings &settings, const SimSettings &sim)
		: settings_(settings), sim_(sim) {}
	std::string name() const override { return "sim-depth"; }
	void setTechnician(std::shared_ptr<const sim::SimTechnician> technician) { technician_ = std::move(technician); }

	static constexpr int kWidth = LectureSimulator::kTofWidth;  // the SR-2's sensor
	static constexpr int kHeight = LectureSimulator::kTofHeight;

private:
	int fps() const override { return settings_.fps; }
	void prepare() override;
	void render(uint64_t nowUs, DepthFrame &frame) override;

	DepthCameraSettings settings_;
	SimSettings sim_;
	LectureSimulator simulator_;
	sim::SimTiming timing_;
	std::shared_ptr<const sim::SimTechnician> technician_;
};

} // namespace depthkey
