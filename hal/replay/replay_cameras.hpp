// The "replay" backends: a recorded sequence folder ([replay] path) played
// back as a colour and a depth camera. Both share one ReplayTimeline, so
// their frames keep the recorded order; each has a status of its own, naming
// the files of its own stream (see replay_timeline.hpp).
#pragma once

#include "hal/camera.hpp"
#include "hal/replay/replay_timeline.hpp"

#include <memory>

namespace depthkey {

class ReplayColourCamera : public ColourCamera
{
public:
	explicit ReplayColourCamera(std::shared_ptr<ReplayTimeline> timeline) : timeline_(std::move(timeline)) {}
	~ReplayColourCamera() override { stop(); }
	std::string name() const override { return "replay-colour"; }
	int start(EventLoop &loop, FrameHandler onFrame, StatusHandler onStatus) override
	{
		return timeline_->attachColour(loop, std::move(onFrame), std::move(onStatus));
	}
	void stop() override { timeline_->detachColour(); }
	DeviceStatus status() const override { return timeline_->colourStatus(); }
	bool freeRunning() const override { return timeline_->settings().realtime; }

private:
	std::shared_ptr<ReplayTimeline> timeline_;
};

class ReplayDepthCamera : public DepthCamera
{
public:
	explicit ReplayDepthCamera(std::shared_ptr<ReplayTimeline> timeline) : timeline_(std::move(timeline)) {}
	~ReplayDepthCamera() override { stop(); }
	std::string name() const override { return "replay-depth"; }
	int start(EventLoop &loop, FrameHandler onFrame, StatusHandler onStatus) override
	{
		return timeline_->attachDepth(loop, std::move(onFrame), std::move(onStatus));
	}
	void stop() override { timeline_->detachDepth(); }
	DeviceStatus status() const override { return timeline_->depthStatus(); }

private:
	std::shared_ptr<ReplayTimeline> timeline_;
};

} // namespace depthkey
