// Plays a recorded sequence folder back on the event loop: one timeline per
// folder, shared by the replay colour and depth cameras, so their frames
// come in the recorded order, paced as recorded (realtime) or one per loop
// iteration (as fast as the daemon takes them).
//
// Frames are re-stamped onto this run's CLOCK_MONOTONIC (start + recorded
// offset, + the sequence's length per loop) so that the daemon's freshness
// checks work; pixels and the offsets between frames are exactly those
// recorded.
//
// Each camera has a status of its own (issue 31): a bad colour file makes
// the colour camera Lost, naming that file, and leaves depth streaming. A
// frame that cannot be played (unreadable, the wrong pixel type, a colour
// size other than [colour]'s, a timestamp the frame before already had) is
// dropped and counted in its camera's status; once found bad it is skipped
// on later loops without being read again. A camera goes Lost at its first
// bad frame and back to Streaming only after kRecoverFrames good ones in a
// row, so a folder of bad files changes the status (and logs) a few times,
// not once a frame.
//
// The frames are read and decoded ahead of play on a thread of its own
// (ReplayPrefetch, issue 29 §2); the timer only hands a decoded frame over.
// When the reader is behind, a frame goes out as soon as it is read, with
// its recorded (re-stamped) timestamp: the loop never waits for it.
#pragma once

#include "hal/camera.hpp"
#include "hal/recording/sequence_reader.hpp"
#include "hal/replay/replay_prefetch.hpp"
#include "settings/settings.hpp"

#include <vector>

namespace depthkey {

// What one camera of the timeline is given: its handlers, its status, where
// it is in its index and which of its frames were found bad.
template<typename Frame>
struct ReplayTrack {
	typename Camera<Frame>::FrameHandler onFrame;
	typename Camera<Frame>::StatusHandler onStatus;
	DeviceStatus status;
	size_t next = 0;
	std::vector<bool> refused; // per index entry: found bad, skipped from now on
	int goodInRow = 0;

	bool attached() const { return static_cast<bool>(onFrame); }
	void setStatus(DeviceState state, int error, const std::string &detail)
	{
		if (status.set(state, error, detail) && onStatus)
			onStatus(status);
	}
};

class ReplayTimeline
{
public:
	// A colour frame is played only at colourWidth x colourHeight ([colour]'s
	// size: the shared memory, the mapping and the board are made for it);
	// 0 x 0 plays any size (the tools).
	explicit ReplayTimeline(const ReplaySettings &settings, int colourWidth = 0, int colourHeight = 0)
		: settings_(settings), colourWidth_(colourWidth), colourHeight_(colourHeight) {}

	// Good frames in a row that bring a camera back from Lost.
	static constexpr int kRecoverFrames = 10;

	int attachColour(EventLoop &loop, ColourCamera::FrameHandler onFrame, ColourCamera::StatusHandler onStatus);
	int attachDepth(EventLoop &loop, DepthCamera::FrameHandler onFrame, DepthCamera::StatusHandler onStatus);
	void detachColour();
	void detachDepth();

	DeviceStatus colourStatus() const { return colour_.status; }
	DeviceStatus depthStatus() const { return depth_.status; }
	const ReplaySettings &settings() const { return settings_; }
	bool plays(const ReplaySettings &settings, int colourWidth, int colourHeight) const
	{
		return settings_ == settings && colourWidth_ == colourWidth && colourHeight_ == colourHeight;
	}

private:
	void begin(EventLoop &loop);
	void detached();
	void open();
	void startTrack(ReplayTrack<ColourFrame> &track);
	void startTrack(ReplayTrack<DepthFrame> &track);
	void scheduleNext();
	void emitNext();
	void onFrameRead();
	template<typename Frame>
	bool emit(ReplayTrack<Frame> &track, const std::vector<SequenceEntry> &index);
	uint64_t localNs(uint64_t recordedNs) const;

	ReplaySettings settings_;
	int colourWidth_, colourHeight_;
	EventLoop *loop_ = nullptr;
	EventSource timer_;
	SequenceReader reader_;
	bool opened_ = false;
	bool skipped_ = false; // the last timer delivered no frame
	bool waiting_ = false; // the next frame is being read: onFrameRead() plays it
	ReplayTrack<ColourFrame> colour_;
	ReplayTrack<DepthFrame> depth_;
	uint64_t firstNs_ = 0, lengthNs_ = 0, startNs_ = 0, loops_ = 0;
	// After reader_: its thread is joined before the reader it uses goes.
	ReplayPrefetch prefetch_;
};

} // namespace depthkey
