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
#include "hal/sim/sim_render_thread.hpp"
#include "hal/sim/sim_technician.hpp"
#include "hal/sim/sim_timing.hpp"
#include "settings/settings.hpp"

#include <algorithm>
#include <memory>

namespace depthkey {

// What the simulated cameras share: a periodic timer on the event loop at
// whose ticks frames are captured, rendered on a thread of the camera's own
// (hal/sim/sim_render_thread.hpp: the simulator's cost, not the box's) into
// a reused buffer, and delivered on the loop once rendered, as a real
// camera's frame arrives a transfer after its capture. A render still
// running at the next tick drops that tick's frame (counted in
// droppedFrames), as a real camera drops frames the host does not take in
// time. At most one frame is in flight. A frame made in the camera's own
// storage stays as delivered until the next is delivered (a handler may keep
// a pointer to it meanwhile: daemon/board_output.hpp's waiting picture), so
// the next render goes into the other of two buffers: the second is
// allocated by the first frame made in it, and reused after.
//
// A final camera's destructor must stop() it: a render in progress calls
// render(), which its members serve.
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
		stop();
		loop_ = &loop;
		onFrame_ = std::move(onFrame);
		prepare();
		sequence_ = 0;
		lastCaptureUs_ = 0;
		int ret = renderer_.start(loop, threadName(), [this] { render(captureUs_, *rendering_); },
					  [this] { deliver(); });
		if (ret < 0)
			return ret;
		ret = loop.addPeriodic(1000000u / fps(), [this] { capture(); }, timer_);
		if (ret < 0) {
			renderer_.stop();
			return ret;
		}
		status_ = { DeviceState::Streaming, 0, "" };
		onStatus(status_);
		return 0;
	}
	// A frame being rendered is finished first, and not delivered.
	void stop() override
	{
		timer_.reset();
		renderer_.stop();
		status_ = { DeviceState::Stopped, 0, "", status_.droppedFrames };
	}
	DeviceStatus status() const override { return status_; }

protected:
	// The render thread's name (15 characters at most), e.g. "dk-sim-colour".
	virtual const char *threadName() const = 0;
	virtual int fps() const = 0;
	virtual void prepare() = 0;
	// Renders the scene for capture time nowUs; frame.sequence is the
	// previous frame's number. Runs on the render thread: it may use only
	// what the loop leaves alone while the camera streams.
	virtual void render(uint64_t nowUs, Frame &frame) = 0;
	// How long before the timer's tick frame n (from 0) was captured: its
	// timestamp and the scene it shows.
	virtual uint64_t captureDelayUs(uint64_t /*n*/) const { return 0; }

private:
	void capture()
	{
		renderer_.deliverFinished(); // the last frame, if its wake-up is still to come
		if (renderer_.busy()) {
			status_.droppedFrames++; // this tick's frame is never made
			return;
		}
		uint64_t now = loop_->nowUs();
		// A camera's timestamps only go forward. The capture instant is the
		// tick less its jitter; a tick the loop ran late followed by one on
		// time could put it before the last frame's (a late tick of 4+ ms
		// at 50 fps with 8 ms of jitter): then just after it instead.
		captureUs_ = std::max(now - std::min(now, captureDelayUs(sequence_)), lastCaptureUs_ + 1);
		lastCaptureUs_ = captureUs_;
		Frame *lent = lender_ ? lender_() : nullptr;
		// own_ stays empty while frames are lent.
		rendering_ = lent ? lent : delivered_ == &own_[0] ? &own_[1] : &own_[0];
		rendering_->sequence = sequence_;
		renderer_.begin();
	}
	void deliver()
	{
		Frame &frame = *rendering_;
		frame.timestampNs = captureUs_ * 1000u;
		frame.sequence = ++sequence_;
		delivered_ = &frame;
		onFrame_(frame);
	}

	EventLoop *loop_ = nullptr;
	EventSource timer_;
	FrameHandler onFrame_;
	FrameLender lender_;
	Frame own_[2];
	// The frame in flight: where it is made and when it was captured.
	Frame *rendering_ = &own_[0];
	const Frame *delivered_ = nullptr; // the last frame delivered, whichever buffer
	uint64_t captureUs_ = 0, lastCaptureUs_ = 0;
	uint64_t sequence_ = 0; // the last frame's number, whichever buffer it was made in
	DeviceStatus status_;
	SimRenderThread renderer_; // last: stopped before the members a render uses go
};

class SimColourCamera final : public PeriodicSimCamera<ColourFrame>
{
public:
	SimColourCamera(const ColourCameraSettings &settings, const SimSettings &sim)
		: settings_(settings), sim_(sim) {}
	~SimColourCamera() override { stop(); }
	std::string name() const override { return "sim-colour"; }
	// A calibration session (depthkey-calibrate --live): the technician's
	// pattern instead of the lecture. Shared with the depth camera; set
	// before start() (the render thread reads it).
	void setTechnician(std::shared_ptr<const sim::SimTechnician> technician) { technician_ = std::move(technician); }

private:
	const char *threadName() const override { return "dk-sim-colour"; }
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

class SimDepthCamera final : public PeriodicSimCamera<DepthFrame>
{
public:
	SimDepthCamera(const DepthCameraSettings &settings, const SimSettings &sim)
		: settings_(settings), sim_(sim) {}
	~SimDepthCamera() override { stop(); }
	std::string name() const override { return "sim-depth"; }
	void setTechnician(std::shared_ptr<const sim::SimTechnician> technician) { technician_ = std::move(technician); }

	static constexpr int kWidth = LectureSimulator::kTofWidth;  // the SR-2's sensor
	static constexpr int kHeight = LectureSimulator::kTofHeight;

private:
	const char *threadName() const override { return "dk-sim-depth"; }
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
