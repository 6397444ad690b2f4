// A camera the test drives by hand: it delivers the frames and states the
// test tells it to, on the daemon's own event loop.
#pragma once

#include "hal/camera.hpp"

namespace depthkey::test {

template<typename Frame>
class FakeCamera : public Camera<Frame>
{
public:
	using typename Camera<Frame>::FrameHandler;
	using typename Camera<Frame>::StatusHandler;

	explicit FakeCamera(std::string name) : name_(std::move(name)) {}

	std::string name() const override { return name_; }
	int start(EventLoop &, FrameHandler onFrame, StatusHandler onStatus) override
	{
		onFrame_ = std::move(onFrame);
		onStatus_ = std::move(onStatus);
		setState(DeviceState::Streaming, 0, "");
		return 0;
	}
	void stop() override { status_ = { DeviceState::Stopped, 0, "" }; }
	DeviceStatus status() const override { return status_; }
	bool freeRunning() const override { return freeRunning_; }

	void deliver(const Frame &frame) { onFrame_(frame); }
	// What the daemon lends for the next frame (hal/camera.hpp), or null.
	void lendFrames(typename Camera<Frame>::FrameLender lender) override { lender_ = std::move(lender); }
	Frame *borrow() { return lender_ ? lender_() : nullptr; }
	// false: a source that waits for the daemon (a replay not in real time).
	void setFreeRunning(bool freeRunning) { freeRunning_ = freeRunning; }
	void setState(DeviceState state, int error, const std::string &detail)
	{
		status_ = { state, error, detail };
		if (onStatus_)
			onStatus_(status_);
	}

private:
	typename Camera<Frame>::FrameLender lender_;
	std::string name_;
	bool freeRunning_ = true;
	FrameHandler onFrame_;
	StatusHandler onStatus_;
	DeviceStatus status_;
};

} // namespace depthkey::test
