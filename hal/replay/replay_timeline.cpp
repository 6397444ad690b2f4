#include "hal/replay/replay_timeline.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>

namespace depthkey {

namespace {

constexpr uint64_t kRetryUs = 2'000'000; // a missing folder may be copied in later
// Not in real time, a frame that is skipped waits this long before the
// next: a folder of bad files would otherwise spin the loop.
constexpr uint64_t kSkippedFrameUs = 40'000;
constexpr uint64_t kDefaultPeriodNs = 40'000'000;

// The mean period of an index, or 0 with fewer than two frames.
uint64_t meanPeriodNs(const std::vector<SequenceEntry> &index)
{
	if (index.size() < 2)
		return 0;
	return (index.back().timestampNs - index.front().timestampNs) / (index.size() - 1);
}

} // namespace

int ReplayTimeline::attachColour(EventLoop &loop, ColourCamera::FrameHandler onFrame,
				 ColourCamera::StatusHandler onStatus)
{
	colour_.onFrame = std::move(onFrame);
	colour_.onStatus = std::move(onStatus);
	if (loop_ && opened_)
		startTrack(colour_);
	begin(loop);
	return 0;
}

int ReplayTimeline::attachDepth(EventLoop &loop, DepthCamera::FrameHandler onFrame,
				DepthCamera::StatusHandler onStatus)
{
	depth_.onFrame = std::move(onFrame);
	depth_.onStatus = std::move(onStatus);
	if (loop_ && opened_)
		startTrack(depth_);
	begin(loop);
	return 0;
}

void ReplayTimeline::detachColour()
{
	colour_.onFrame = nullptr;
	colour_.onStatus = nullptr;
	colour_.status = { DeviceState::Stopped, 0, "", colour_.status.droppedFrames };
	prefetch_.idle<ColourFrame>();
	detached();
}

void ReplayTimeline::detachDepth()
{
	depth_.onFrame = nullptr;
	depth_.onStatus = nullptr;
	depth_.status = { DeviceState::Stopped, 0, "", depth_.status.droppedFrames };
	prefetch_.idle<DepthFrame>();
	detached();
}

// Nobody listens any more: stop, and start afresh (the folder read again) on
// the next attach.
void ReplayTimeline::detached()
{
	if (colour_.attached() || depth_.attached()) {
		// The frame being waited for may have been the one detached.
		if (waiting_ && opened_)
			scheduleNext();
		return;
	}
	prefetch_.stop();
	waiting_ = false;
	timer_.reset();
	loop_ = nullptr;
	opened_ = false;
}

// The first attach opens the folder; the second joins the running timeline
// (its frames scheduled from now on: the first may have had none to play).
void ReplayTimeline::begin(EventLoop &loop)
{
	if (loop_) {
		if (opened_)
			scheduleNext();
		else // the folder is being retried: the newcomer hears why
			for (const DeviceStatus *s : { &colour_.status, &depth_.status })
				if (s->state == DeviceState::Lost) {
					colour_.setStatus(s->state, s->error, s->detail);
					depth_.setStatus(s->state, s->error, s->detail);
					break;
				}
		return;
	}
	loop_ = &loop;
	open();
}

void ReplayTimeline::open()
{
	int ret = reader_.open(settings_.path);
	std::string why = reader_.describeError();
	if (ret >= 0) {
		ret = prefetch_.start(*loop_, reader_, colourWidth_, colourHeight_, settings_.loop,
				      [this] { onFrameRead(); });
		if (ret < 0)
			why = settings_.path + ": cannot start the thread that reads it: " + std::strerror(-ret);
	}
	if (ret < 0) {
		// The folder is both cameras'.
		colour_.setStatus(DeviceState::Lost, ret, why);
		depth_.setStatus(DeviceState::Lost, ret, why);
		loop_->addTimer(kRetryUs, [this] { open(); }, timer_);
		return;
	}
	opened_ = true;
	uint64_t first = UINT64_MAX, last = 0;
	for (const auto *index : { &reader_.colour(), &reader_.depth() })
		if (!index->empty()) {
			first = std::min(first, index->front().timestampNs);
			last = std::max(last, index->back().timestampNs);
		}
	firstNs_ = first;
	// One loop lasts the recording plus one frame period (colour's, else
	// depth's, else 40 ms).
	uint64_t period = meanPeriodNs(reader_.colour());
	if (period == 0)
		period = meanPeriodNs(reader_.depth());
	lengthNs_ = last - first + (period ? period : kDefaultPeriodNs);
	startNs_ = loop_->nowUs() * 1000u;
	loops_ = 0;
	skipped_ = false;
	startTrack(colour_);
	startTrack(depth_);
	scheduleNext();
}

// A frame with the timestamp of the one before cannot be paired apart from
// it (the pairer drops it); it is refused here, where it is counted.
template<typename Frame>
static void refuseRepeatedTimestamps(ReplayTrack<Frame> &track, const std::vector<SequenceEntry> &index)
{
	track.next = 0;
	track.goodInRow = 0;
	track.refused.assign(index.size(), false);
	for (size_t i = 1; i < index.size(); ++i)
		track.refused[i] = index[i].timestampNs == index[i - 1].timestampNs;
}

void ReplayTimeline::startTrack(ReplayTrack<ColourFrame> &track)
{
	refuseRepeatedTimestamps(track, reader_.colour());
	if (track.attached())
		prefetch_.restart<ColourFrame>(track.refused);
	if (reader_.colour().empty()) // a depth-only recording: depth plays, colour says why not
		track.setStatus(DeviceState::Lost, -ENODATA, reader_.dir() + "/rgb.txt: no colour frames recorded");
	else
		track.setStatus(DeviceState::Streaming, 0, "");
}

void ReplayTimeline::startTrack(ReplayTrack<DepthFrame> &track)
{
	refuseRepeatedTimestamps(track, reader_.depth());
	if (track.attached())
		prefetch_.restart<DepthFrame>(track.refused);
	if (reader_.depth().empty())
		track.setStatus(DeviceState::Lost, -ENODATA, reader_.dir() + "/depth.txt: no depth frames recorded");
	else
		track.setStatus(DeviceState::Streaming, 0, "");
}

uint64_t ReplayTimeline::localNs(uint64_t recordedNs) const
{
	return startNs_ + loops_ * lengthNs_ + (recordedNs - firstNs_);
}

void ReplayTimeline::scheduleNext()
{
	waiting_ = false; // the timer plays the next frame
	bool colourLeft = colour_.attached() && colour_.next < reader_.colour().size();
	bool depthLeft = depth_.attached() && depth_.next < reader_.depth().size();
	if (!colourLeft && !depthLeft) {
		const bool anything = (colour_.attached() && !reader_.colour().empty()) ||
				      (depth_.attached() && !reader_.depth().empty());
		if (!anything)
			return; // nothing an attached camera can play; a second attach reschedules
		if (!settings_.loop) {
			const std::string end = settings_.path + ": end of the recording";
			if (colour_.attached())
				colour_.setStatus(DeviceState::Lost, -ENODATA, end);
			if (depth_.attached())
				depth_.setStatus(DeviceState::Lost, -ENODATA, end);
			return;
		}
		loops_++;
		colour_.next = depth_.next = 0;
		colourLeft = colour_.attached() && !reader_.colour().empty();
		depthLeft = depth_.attached() && !reader_.depth().empty();
	}
	uint64_t due = UINT64_MAX;
	if (colourLeft)
		due = reader_.colour()[colour_.next].timestampNs;
	if (depthLeft)
		due = std::min(due, reader_.depth()[depth_.next].timestampNs);
	uint64_t delayUs = skipped_ ? kSkippedFrameUs : 0;
	if (settings_.realtime) {
		uint64_t dueNs = localNs(due), nowNs = loop_->nowUs() * 1000u;
		delayUs = dueNs > nowNs ? (dueNs - nowNs) / 1000u : 0;
	}
	loop_->addTimer(delayUs, [this] { emitNext(); }, timer_);
}

void ReplayTimeline::emitNext()
{
	waiting_ = false;
	bool colourLeft = colour_.attached() && colour_.next < reader_.colour().size();
	bool depthLeft = depth_.attached() && depth_.next < reader_.depth().size();
	// Depth first on equal timestamps: the daemon pairs colour with the
	// newest depth at or before it.
	bool depthNext = depthLeft && (!colourLeft || reader_.depth()[depth_.next].timestampNs <=
							     reader_.colour()[colour_.next].timestampNs);
	bool played = true;
	if (depthNext)
		played = emit(depth_, reader_.depth());
	else if (colourLeft)
		played = emit(colour_, reader_.colour());
	if (!played) { // the reader thread is behind: the frame goes when read, the loop goes on
		waiting_ = true;
		return;
	}
	if (loop_) // a frame handler may have stopped both cameras (a reload)
		scheduleNext();
}

void ReplayTimeline::onFrameRead()
{
	if (waiting_ && loop_)
		emitNext();
}

// A bad frame is dropped and counted; the replay goes on. Its camera goes
// Lost naming the file, and says so again only when the error changes or
// after it came back.
// False when the frame is not read yet (nothing done: emitNext() is
// called again when it is).
template<typename Frame>
bool ReplayTimeline::emit(ReplayTrack<Frame> &track, const std::vector<SequenceEntry> &index)
{
	const size_t i = track.next;
	PrefetchedFrame<Frame> *read = nullptr;
	// A refused frame was never read: the reader thread skips it too.
	if (!track.refused[i] && !(read = prefetch_.take<Frame>()))
		return false;
	track.next++;
	skipped_ = true;
	if (!read) {
		track.status.droppedFrames++;
		return true;
	}
	if (const int ret = read->result; ret < 0) {
		track.refused[i] = true;
		track.status.droppedFrames++;
		track.goodInRow = 0;
		if (track.status.state != DeviceState::Lost || track.status.error != ret)
			track.setStatus(DeviceState::Lost, ret, read->error);
		prefetch_.release(read);
		return true;
	}
	skipped_ = false;
	Frame &frame = read->frame;
	frame.timestampNs = localNs(frame.timestampNs);
	frame.sequence += loops_ * index.size();
	track.onFrame(frame);
	prefetch_.release(read);
	if (track.status.state != DeviceState::Streaming && ++track.goodInRow >= kRecoverFrames)
		track.setStatus(DeviceState::Streaming, 0, "");
	return true;
}

} // namespace depthkey
