// Plays a recorded sequence folder back on the event loop: one timeline per
// folder, shared by the replay colour and depth cameras, so their frames
// come in the recorded order, paced as recorded (realtime) or one per loop
// iteration (as fast as the daemon takes them).
//
// Frames are re-stamped onto this run's CLOCK_MONOTONIC (start + recorded
// offset, + the sequence's length per loop) so that the daemon's freshness
// checks work; pixels and the offsets between frames are exactly those
// recorded.
#pragma once

#include "hal/camera.hpp"
#include "hal/recording/sequence_reader.hpp"
#include "settings/settings.hpp"

namespace depthkey {

class ReplayTimeline
{
public:
	explicit ReplayTimeline(const ReplaySettings &settings) : settings_(settings) {}

	int attachColour(EventLoop &loop, ColourCamera::FrameHandler onFrame, ColourCamera::StatusHandler onStatus);
	int attachDepth(EventLoop &loop, DepthCamera::FrameHandler onFrame, DepthCamera::StatusHandler onStatus);
	void detachColour();
	void detachDepth();

	DeviceStatus status() const { return status_; }
	const ReplaySettings &settings() const { return settings_; }

private:
	void begin(EventLoop &loop);
	void rewind();
	void open();
	void scheduleNext();
	void emitNext();
	void setStatus(DeviceStatus status);
	uint64_t localNs(uint64_t recordedNs) const;

	ReplaySettings settings_;
	EventLoop *loop_ = nullptr;
	EventSource timer_;
	SequenceReader reader_;
	ColourCamera::FrameHandler onColour_;
	DepthCamera::FrameHandler onDepth_;
	ColourCamera::StatusHandler colourStatus_;
	DepthCamera::StatusHandler depthStatus_;
	DeviceStatus status_;
	size_t nextColour_ = 0, nextDepth_ = 0;
	uint64_t firstNs_ = 0, lengthNs_ = 0, startNs_ = 0, loops_ = 0;
	ColourFrame colour_;
	DepthFrame depth_;
};

} // namespace depthkey
