#include "hal/replay/replay_timeline.hpp"

#include <algorithm>
#include <cerrno>

namespace depthkey {

namespace {

constexpr uint64_t kRetryUs = 2'000'000; // a missing folder may be copied in later

} // namespace

int ReplayTimeline::attachColour(EventLoop &loop, ColourCamera::FrameHandler onFrame,
				 ColourCamera::StatusHandler onStatus)
{
	onColour_ = std::move(onFrame);
	colourStatus_ = std::move(onStatus);
	begin(loop);
	return 0;
}

int ReplayTimeline::attachDepth(EventLoop &loop, DepthCamera::FrameHandler onFrame,
				DepthCamera::StatusHandler onStatus)
{
	onDepth_ = std::move(onFrame);
	depthStatus_ = std::move(onStatus);
	begin(loop);
	return 0;
}

void ReplayTimeline::detachColour()
{
	onColour_ = nullptr;
	colourStatus_ = nullptr;
	if (!onDepth_)
		rewind();
}

void ReplayTimeline::detachDepth()
{
	onDepth_ = nullptr;
	depthStatus_ = nullptr;
	if (!onColour_)
		rewind();
}

// Nobody listens any more: stop, and start afresh on the next attach.
void ReplayTimeline::rewind()
{
	timer_.reset();
	loop_ = nullptr;
}

void ReplayTimeline::setStatus(DeviceStatus status)
{
	status_ = std::move(status);
	if (colourStatus_)
		colourStatus_(status_);
	if (depthStatus_)
		depthStatus_(status_);
}

// The first attach opens the folder; the second joins the running timeline.
void ReplayTimeline::begin(EventLoop &loop)
{
	if (loop_)
		return;
	loop_ = &loop;
	open();
}

void ReplayTimeline::open()
{
	int ret = reader_.open(settings_.path);
	if (ret < 0) {
		setStatus({ DeviceState::Lost, ret, reader_.describeError() });
		loop_->addTimer(kRetryUs, [this] { open(); }, timer_);
		return;
	}
	uint64_t first = UINT64_MAX, last = 0;
	for (const auto *index : { &reader_.colour(), &reader_.depth() })
		if (!index->empty()) {
			first = std::min(first, index->front().timestampNs);
			last = std::max(last, index->back().timestampNs);
		}
	firstNs_ = first;
	// One loop lasts the recording plus one colour period (or 40 ms).
	uint64_t period = reader_.colour().size() > 1
				  ? (reader_.colour().back().timestampNs - reader_.colour().front().timestampNs) /
					    (reader_.colour().size() - 1)
				  : 40'000'000u;
	lengthNs_ = last - first + period;
	startNs_ = loop_->nowUs() * 1000u;
	nextColour_ = nextDepth_ = 0;
	loops_ = 0;
	setStatus({ DeviceState::Streaming, 0, "" });
	scheduleNext();
}

uint64_t ReplayTimeline::localNs(uint64_t recordedNs) const
{
	return startNs_ + loops_ * lengthNs_ + (recordedNs - firstNs_);
}

void ReplayTimeline::scheduleNext()
{
	bool colourLeft = onColour_ && nextColour_ < reader_.colour().size();
	bool depthLeft = onDepth_ && nextDepth_ < reader_.depth().size();
	if (!colourLeft && !depthLeft) {
		if (!settings_.loop) {
			setStatus({ DeviceState::Lost, -ENODATA, settings_.path + ": end of the recording" });
			return;
		}
		loops_++;
		nextColour_ = nextDepth_ = 0;
		colourLeft = onColour_ && !reader_.colour().empty();
		depthLeft = onDepth_ && !reader_.depth().empty();
		if (!colourLeft && !depthLeft)
			return;
	}
	uint64_t due = UINT64_MAX;
	if (colourLeft)
		due = reader_.colour()[nextColour_].timestampNs;
	if (depthLeft)
		due = std::min(due, reader_.depth()[nextDepth_].timestampNs);
	uint64_t delayUs = 0;
	if (settings_.realtime) {
		uint64_t dueNs = localNs(due), nowNs = loop_->nowUs() * 1000u;
		delayUs = dueNs > nowNs ? (dueNs - nowNs) / 1000u : 0;
	}
	loop_->addTimer(delayUs, [this] { emitNext(); }, timer_);
}

void ReplayTimeline::emitNext()
{
	bool colourLeft = onColour_ && nextColour_ < reader_.colour().size();
	bool depthLeft = onDepth_ && nextDepth_ < reader_.depth().size();
	// Depth first on equal timestamps: the daemon pairs colour with the
	// newest depth at or before it.
	bool depthNext = depthLeft && (!colourLeft || reader_.depth()[nextDepth_].timestampNs <=
							     reader_.colour()[nextColour_].timestampNs);
	int ret = 0;
	if (depthNext) {
		ret = reader_.readDepth(nextDepth_++, depth_);
		if (ret >= 0) {
			depth_.timestampNs = localNs(depth_.timestampNs);
			depth_.sequence += loops_ * reader_.depth().size();
			onDepth_(depth_);
		}
	} else if (colourLeft) {
		ret = reader_.readColour(nextColour_, colour_);
		// A sequence with mask/ is scored live as the simulator is (issue 29).
		if (ret >= 0 && reader_.hasMask())
			ret = reader_.readMask(nextColour_, colour_.truth);
		else if (ret >= 0)
			colour_.truth.resize(0, 0);
		nextColour_++;
		if (ret >= 0) {
			colour_.timestampNs = localNs(colour_.timestampNs);
			colour_.sequence += loops_ * reader_.colour().size();
			onColour_(colour_);
		}
	}
	// A bad frame is reported and skipped; the replay goes on.
	if (ret < 0)
		setStatus({ DeviceState::Lost, ret, reader_.describeError() });
	else if (status_.state != DeviceState::Streaming)
		setStatus({ DeviceState::Streaming, 0, "" });
	scheduleNext();
}

} // namespace depthkey
