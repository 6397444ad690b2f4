#include "daemon/frame_outputs.hpp"

#include "daemon/log.hpp"
#include "hal/depthkey_shm.h"

#include <cerrno>

namespace depthkey {

int FrameOutputs::open(const Settings &settings, const OutputGeometry &geometry)
{
	settings_ = settings.output;
	geometry_ = geometry;
	// Over a second without a keyed frame is an outage, not a hiccup: a new
	// stream, too, starts its own time.
	slots_.configure(1'000'000'000ull / static_cast<uint64_t>(settings.colour.fps > 0 ? settings.colour.fps : 25),
			 1'000'000'000ull);
	if (!sink_)
		sink_ = makeSink_(settings);
	return openSink();
}

int FrameOutputs::openSink()
{
	int ret = sink_->open(settings_, geometry_.width, geometry_.height, geometry_.boardWidth,
			      geometry_.boardHeight);
	sinkOpen_ = ret >= 0;
	const bool first = !attempted_;
	attempted_ = true;
	if (ret == -EBUSY && first) {
		sink_->remove(); // what this open created before the busy one, e.g. the composite
		return ret;      // the daemon exits with this (Daemon::start)
	}
	if (ret < 0)
		logger().errorOnce("output", "cannot open shared-memory output: " + sink_->describeError(),
				   { { "DEVICE", "shm" }, { "ERROR", errnoText(ret) } });
	else
		logger().clearError("output", "shared-memory output open", { { "DEVICE", "shm" } });
	return ret;
}

int FrameOutputs::reopen(const Settings &settings, const OutputGeometry &geometry)
{
	if (!sink_)
		return 0;
	sink_->close();
	return open(settings, geometry);
}

void FrameOutputs::apply(const Settings &previous, Settings &next, const OutputGeometry &geometry,
			 const std::string &configPath)
{
	const bool sizeChanged = previous.colour.width != next.colour.width ||
				 previous.colour.height != next.colour.height;
	// The virtual webcam (output.v4l2_device) is no shared memory: changing
	// it alone must not re-create the objects under their readers.
	const bool outputChanged = !sameSharedMemory(previous.output, next.output);
	if (!outputChanged && !sizeChanged)
		return;
	if (reopen(next, geometry) >= 0 || !outputChanged)
		return;
	logger().error("output settings not applied: " + sink_->describeError() + "; keeping the previous [output]",
		       { { "DEVICE", "shm" }, { "CONFIG_FILE", configPath } });
	const std::string webcam = next.output.v4l2Device;
	next.output = previous.output;
	next.output.v4l2Device = webcam;
	open(next, geometry);
}

void FrameOutputs::close()
{
	if (sink_)
		sink_->close();
}

void FrameOutputs::remove()
{
	if (sink_)
		sink_->remove();
}

// -EUCLEAN: the stream's object had been shrunk or its header changed by
// someone else, and the writer repaired it and published the frame
// (hal/shm_ring_guard.cpp). Said once per change, and not a failed frame.
int FrameOutputs::noteRepair(int ret)
{
	if (ret != -EUCLEAN)
		return ret;
	logger().errorOnce("output-repaired", "shared-memory output repaired: " + sink_->describeError(),
			   { { "DEVICE", "shm" }, { "ERROR", errnoText(ret) } });
	return 0;
}

int FrameOutputs::publish(const OutputFrame &frame)
{
	if (!sink_)
		return -EBADF;
	if (!sinkOpen_) {
		if (int ret = openSink(); ret < 0)
			return ret;
	}
	fillSkippedSlots(frame);
	int ret = frame.boardMaker ? sink_->publishBoard(*frame.boardMaker, frame.captureNs, frame.flags)
		  : frame.composite ? sink_->publishComposite(*frame.composite, frame.captureNs, frame.flags)
				    : sink_->publishComposite(*frame.compositeInputs, frame.captureNs, frame.flags);
	ret = noteRepair(ret);
	if (ret >= 0)
		ret = noteRepair(sink_->publishLecturer(frame.colour, frame.alpha, frame.captureNs, frame.flags));
	if (ret >= 0 && frame.boardLecturer && !frame.boardMaker)
		ret = noteRepair(sink_->publishBoardLecturer(*frame.boardLecturer, frame.captureNs, frame.flags));
	if (ret < 0)
		logger().errorOnce("output", "cannot publish: " + sink_->describeError(),
				   { { "DEVICE", "shm" }, { "ERROR", errnoText(ret) } });
	// NO SIGNAL frames (no colour) are stamped by the loop's timer, not a
	// capture: the slots start again with the next keyed frame.
	if (ret < 0 || !frame.colour)
		slots_.reset();
	lastKeyedFlags_ = frame.flags;
	return ret;
}

void FrameOutputs::fillSkippedSlots(const OutputFrame &frame)
{
	if (!frame.colour)
		return;
	const uint64_t skipped = slots_.skippedBefore(frame.captureNs);
	for (uint64_t slot = 1; slot <= skipped; slot++) {
		if (noteRepair(sink_->repeatLast(slots_.slotNs(slot), lastKeyedFlags_ | DK_SHM_FLAG_REPEATED)) < 0)
			return; // publish() below says what failed
		repeated_++;
	}
}

bool FrameOutputs::sampleReaders(uint64_t nowNs)
{
	if (!sink_ || !sinkOpen_)
		return false;
	ReaderCounts now = sink_->countReaders(nowNs);
	if (now == readers_)
		return false;
	const bool attachedChanged = (now.total() > 0) != (readers_.total() > 0);
	readers_ = now;
	readerEverAttached_ = readerEverAttached_ || now.total() > 0;
	logger().info("readers: composite " + std::to_string(now.composite) + ", lecturer " +
			      std::to_string(now.lecturer) + ", board-geometry lecturer " +
			      std::to_string(now.boardLecturer),
		      { { "DEVICE", "shm" } });
	return attachedChanged;
}

} // namespace depthkey
