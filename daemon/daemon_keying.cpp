// How a colour frame goes from the pairing ring through the keying worker
// (daemon/keying_worker.hpp) to the outputs (issue 28). The loop hands a
// due frame over and goes on; the worker runs the pipeline; its result
// comes back to the loop, which warps it onto the board, offers it to the
// previews and publishes it. Publishing stays on the loop: the shared
// memory, the virtual webcam, the preview and the recorder are the loop's
// (re-opened on reloads and geometry changes, sampled for readers, fed NO
// SIGNAL frames by its timer), and one thread writing them needs no lock.
#include "daemon/daemon.hpp"

#include "daemon/log.hpp"
#include "hal/depthkey_shm.h"

#include <unistd.h>

namespace depthkey {

void Daemon::keyDueFrames(bool makeRoom)
{
	const uint64_t nowNs = loop_.nowUs() * 1000u;
	PairingQueue &queue = pairing_.queue();
	PairingQueue::Keying keying;
	// A source that waits for the daemon (a replay not in real time) loses
	// no frame: the loop waits for the worker instead.
	const bool mayDrop = !colour_ || colour_->freeRunning();
	submitting_ = true;
	while (queue.next(nowNs, keying, makeRoom)) {
		makeRoom = false; // one frame's room
		const uint64_t shedBefore = keyer_.dropped();
		KeyingJob *job = keyer_.nextJob(mayDrop);
		if (!job) { // the worker is stopped: the daemon is stopping
			queue.pop();
			continue;
		}
		// A frame shed: the student keeps seeing the last one out (issue 29).
		if (keyer_.dropped() != shedBefore)
			liveScore_.addRepeated(job->colour.truth, job->colour.timestampNs);
		job->setDepth(keying.depth);
		job->makeComposite = compositeReadHere(nowNs);
		queue.popInto(job->colour); // a swap: no copy
		keyer_.submit(job);
	}
	submitting_ = false;
	if (!queue.held()) {
		keyTimer_.reset();
		return;
	}
	const uint64_t deadlineNs = queue.nextDeadlineNs();
	const uint64_t waitUs = deadlineNs > nowNs ? (deadlineNs - nowNs + 999) / 1000 : 0;
	loop_.addTimer(waitUs, [this] { keyDueFrames(); }, keyTimer_);
}

void Daemon::keyOnWorker(KeyingJob &job)
{
	if (keyingStalled_.load(std::memory_order_relaxed)) {
		keyer_.waitForStop(); // TEST-ONLY: a wedged keying, until SIGTERM
		return;
	}
	if (factory_.beforeKeying)
		factory_.beforeKeying();
	if (testFault_ == TestFault::Slow) // TEST-ONLY: a box too slow to key every frame
		usleep(kSlowKeyingUs);
	// The composite for the recorder is made in its shared memory; the
	// pipeline makes an image of it only for the readers on the loop.
	pipeline_.setMakeComposite(job.makeComposite);
	if (job.newestDepth())
		pipeline_.process(job.colour, job.depth, output_);
	else
		pipeline_.passThrough(job.colour, output_);
}

void Daemon::onKeyed(KeyingJob &job)
{
	if (keyingStalled_.load(std::memory_order_relaxed))
		return; // the stall's frame was never keyed
	inResult_ = true;
	const uint64_t startUs = loop_.nowUs();
	noSignal_.forget();
	const ColourFrame &frame = job.colour;
	const DepthFrame *depth = job.newestDepth();
	uint32_t flags = DK_SHM_FLAG_COLOUR_OK;
	if (depth)
		flags |= DK_SHM_FLAG_DEPTH_OK | DK_SHM_FLAG_ONLINE;
	if (depth && job.depth.stale())
		flags |= DK_SHM_FLAG_DEPTH_STALE; // keyed all the same: no blink (issue 29)
	// Board geometry: the lecturer warped onto the board's picture. Without
	// depth within a second (FramePairer::kLostNs: the depth camera offline
	// or silent) the board's picture alone goes out, marked offline: it is the
	// lecture's content, and warping the whole colour frame would cost the
	// CPU a slow box needs to get depth back.
	// Read nowhere but in the shared memory, it is made there (issue 29 §2).
	BoardFrameMaker *inPlace = nullptr;
	const int opacityQ8 = opacityToQ8(settings_.composite.opacity);
	if (depth && !boardImagesReadHere(startUs * 1000u))
		inPlace = board_.composeInPlace(frame.rgb, output_.alpha, pipeline_.roi(), opacityQ8);
	else if (depth)
		board_.compose(frame.rgb, output_.alpha, pipeline_.roi(), opacityQ8);
	else
		board_.showBoardOnly();
	stageDumps_.onKeyedFrame(frame, depth, status_.colourFrames(), pipelineView());
	CompositeInputs parts;
	if (depth)
		parts = pipeline_.compositeInputs(frame.rgb, output_.alpha);
	RecordedPictures recorded = recordedPictures(&frame.rgb, depth != nullptr);
	if (inPlace) { // made only in the shared memory
		recorded.composite = nullptr;
		recorded.boardLayer = nullptr;
	}
	recorded.compositeInSharedMemory = !recorded.composite;
	preview_.offer(&frame, depth, depth ? &pipeline_.trimap() : nullptr, output_, recorded, frame.timestampNs,
		       loop_.nowUs() * 1000u);
	publish(&frame.rgb, depth ? &parts : nullptr, frame.timestampNs, flags, inPlace);
	scorePublished(frame, depth != nullptr);
	pipelineStatus_ = pipeline_.status();
	// The frame's work, wherever it ran: the pipeline on the worker and
	// the rest here; not the time it waited for the worker.
	status_.countKeying(job.keyingUs + (loop_.nowUs() - startUs));
	betweenFrames();
	inResult_ = false;
}

void Daemon::betweenFrames()
{
	board_.takeWaitingPicture();
	if (snapshotWanted_) {
		snapshotWanted_ = false;
		std::string message;
		const int ret = stageDumps_.writeSnapshot(pairing_.queue().pairer().newest(), pipelineView(), message);
		preview_.answerSnapshot(ret, message);
	}
	// A reload restarts cameras and clears the pairing ring: not while
	// keyDueFrames reads it (a source that waits for the daemon has the
	// loop take results there); the next result applies it.
	if (pendingReload_ && !submitting_) {
		auto reload = std::move(*pendingReload_);
		pendingReload_.reset();
		applyNow(reload.first, reload.second);
	}
}

// What went out against the truth of the time it stands for (issue 29),
// here on the loop where every published frame is known, not on the
// keying worker. Without a truth (a real camera) nothing is done.
void Daemon::scorePublished(const ColourFrame &frame, bool keyed)
{
	const bool boardOnly = !keyed && board_.boardGeometry();
	depthKeyed_ = depthKeyed_ || keyed;
	if (boardOnly && depthKeyed_)
		boardOnlyFrames_++;
	if (frame.truth.empty())
		return;
	// The lecturer layer in camera geometry: the keyed alpha, the colour
	// frame unkeyed (all lecturer) in camera geometry, none at all when the
	// board's picture went out alone.
	if (boardOnly)
		liveScore_.addWithoutLecturer(frame.truth, frame.timestampNs);
	else
		liveScore_.add(output_.alpha, frame.truth, frame.timestampNs);
}

// In board geometry the webcam and the preview take the board's composite:
// the pipeline's camera-geometry image is then for the stage dumps only.
bool Daemon::compositeReadHere(uint64_t nowNs) const
{
	return (!board_.boardGeometry() && (webcam_.enabled() || preview_.wantsComposite(nowNs))) ||
	       stageDumps_.readsStages();
}

bool Daemon::boardImagesReadHere(uint64_t nowNs) const
{
	return webcam_.enabled() || preview_.wantsComposite(nowNs) || preview_.wantsLecturer(nowNs) ||
	       stageDumps_.readsStages() || snapshotWanted_;
}

const RgbImage *Daemon::publishedComposite(const RgbImage *colour, bool fromParts) const
{
	if (board_.boardGeometry())
		return &board_.composite();
	if (!output_.composite.empty())
		return &output_.composite;
	return fromParts ? nullptr : colour;
}

RecordedPictures Daemon::recordedPictures(const RgbImage *colour, bool fromParts) const
{
	const bool board = board_.boardGeometry();
	return { publishedComposite(colour, fromParts), board ? &board_.lecturer() : nullptr, &board_.picture() };
}

void Daemon::publish(const RgbImage *colour, const CompositeInputs *parts, uint64_t captureNs, uint32_t flags,
		     BoardFrameMaker *boardMaker)
{
	if (keyingStalled_.load(std::memory_order_relaxed))
		return; // TEST-ONLY: NO SIGNAL frames stop too
	const bool boardImages = board_.boardGeometry() && !boardMaker;
	const RgbImage *composite = boardMaker ? nullptr : publishedComposite(colour, parts != nullptr);
	// Never waits; a full or lost device is its own status (hal/v4l2/v4l2_output.hpp).
	if (composite)
		webcam_.write(*composite);
	if (outputs_.publish({ composite, parts, colour, output_.alpha, boardImages ? &board_.lecturer() : nullptr,
			       captureNs, flags, boardMaker }) < 0)
		return;
	status_.countPublished(flags & DK_SHM_FLAG_ONLINE);
}

} // namespace depthkey
