#include "hal/replay/replay_prefetch.hpp"

#include <pthread.h>
#include <cerrno>
#include <sys/epoll.h>
#include <sys/eventfd.h>
#include <system_error>
#include <unistd.h>

namespace depthkey {

namespace {

std::string sizeText(int width, int height)
{
	return std::to_string(width) + "x" + std::to_string(height);
}

} // namespace

template<typename Frame>
void ReplayPrefetch::Lane<Frame>::reset(uint64_t newGeneration)
{
	generation = newGeneration;
	produced = consumed = 0;
	next = 0;
	pass = 0;
	active = false;
	// What was read for the old generation goes; a slot being read or held
	// is freed by whoever has it.
	for (auto &slot : slots)
		if (slot.state == PrefetchedFrame<Frame>::State::Ready)
			slot.state = PrefetchedFrame<Frame>::State::Free;
}

// The next index the timeline will take: as ReplayTimeline walks the
// stream (its end, then index 0 again when it loops; refused frames
// skipped without a read).
template<typename Frame>
void ReplayPrefetch::Lane<Frame>::advance(bool loops)
{
	const size_t n = refused.size();
	for (size_t step = 0; step < n; ++step) {
		if (++next == n) {
			if (!loops) {
				active = false;
				return;
			}
			next = 0;
			pass++;
		}
		if (!refused[next])
			return;
	}
	active = false; // every frame refused: nothing left to read
}

template<typename Frame>
bool ReplayPrefetch::Lane<Frame>::wantsRead() const
{
	return active && slots[produced % kAhead].state == PrefetchedFrame<Frame>::State::Free;
}

template<>
ReplayPrefetch::Lane<ColourFrame> &ReplayPrefetch::lane<ColourFrame>()
{
	return colour_;
}

template<>
ReplayPrefetch::Lane<DepthFrame> &ReplayPrefetch::lane<DepthFrame>()
{
	return depth_;
}

int ReplayPrefetch::start(EventLoop &loop, SequenceReader &reader, int colourWidth, int colourHeight, bool loops,
			  std::function<void()> ready)
{
	stop();
	reader_ = &reader;
	colourWidth_ = colourWidth;
	colourHeight_ = colourHeight;
	loops_ = loops;
	ready_ = std::move(ready);
	colour_.index = &reader.colour();
	depth_.index = &reader.depth();
	if (!eventFd_.isValid()) {
		eventFd_.reset(eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC));
		if (!eventFd_.isValid())
			return -errno;
	}
	if (int ret = loop.addIo(eventFd_.get(), EPOLLIN, [this](uint32_t) { onReadable(); }, source_); ret < 0)
		return ret;
	stop_ = false;
	try {
		thread_ = std::thread([this] { run(); });
	} catch (const std::system_error &e) {
		source_.reset();
		return -(e.code().value() ? e.code().value() : EAGAIN);
	}
	// Named here, before anybody can look, so that top -H, make
	// bench-process and the CPU-share test (tests/process/live_vs_offline.sh)
	// tell the replay's decoding apart.
	pthread_setname_np(thread_.native_handle(), "dk-replay");
	return 0;
}

void ReplayPrefetch::stop()
{
	{
		std::lock_guard lock(mutex_);
		stop_ = true;
	}
	wake_.notify_all();
	if (thread_.joinable())
		thread_.join();
	source_.reset();
	std::lock_guard lock(mutex_);
	colour_.reset(++generations_);
	depth_.reset(++generations_);
}

template<typename Frame>
void ReplayPrefetch::restart(const std::vector<bool> &refused)
{
	{
		std::lock_guard lock(mutex_);
		Lane<Frame> &l = lane<Frame>();
		l.reset(++generations_);
		l.refused = refused;
		l.active = !refused.empty();
		if (l.active && refused[0])
			l.advance(loops_);
	}
	wake_.notify_all();
}

template<typename Frame>
void ReplayPrefetch::idle()
{
	std::lock_guard lock(mutex_);
	lane<Frame>().reset(++generations_);
}

template<typename Frame>
PrefetchedFrame<Frame> *ReplayPrefetch::take()
{
	std::lock_guard lock(mutex_);
	Lane<Frame> &l = lane<Frame>();
	if (l.consumed == l.produced)
		return nullptr;
	PrefetchedFrame<Frame> &slot = l.slots[l.consumed % kAhead];
	slot.state = PrefetchedFrame<Frame>::State::Held;
	return &slot;
}

template<typename Frame>
void ReplayPrefetch::release(PrefetchedFrame<Frame> *frame)
{
	{
		std::lock_guard lock(mutex_);
		Lane<Frame> &l = lane<Frame>();
		frame->state = PrefetchedFrame<Frame>::State::Free;
		if (frame->generation == l.generation)
			l.consumed++;
	}
	wake_.notify_all();
}

template void ReplayPrefetch::restart<ColourFrame>(const std::vector<bool> &);
template void ReplayPrefetch::restart<DepthFrame>(const std::vector<bool> &);
template void ReplayPrefetch::idle<ColourFrame>();
template void ReplayPrefetch::idle<DepthFrame>();
template PrefetchedFrame<ColourFrame> *ReplayPrefetch::take<ColourFrame>();
template PrefetchedFrame<DepthFrame> *ReplayPrefetch::take<DepthFrame>();
template void ReplayPrefetch::release<ColourFrame>(PrefetchedFrame<ColourFrame> *);
template void ReplayPrefetch::release<DepthFrame>(PrefetchedFrame<DepthFrame> *);

void ReplayPrefetch::run()
{
	std::unique_lock lock(mutex_);
	for (;;) {
		wake_.wait(lock, [this] { return stop_ || colour_.wantsRead() || depth_.wantsRead(); });
		if (stop_)
			return;
		// The stream whose next frame plays first: the same pass (loop)
		// compares timestamps; an earlier pass comes first.
		bool colourFirst = colour_.wantsRead();
		if (colourFirst && depth_.wantsRead()) {
			const uint64_t c = (*colour_.index)[colour_.next].timestampNs;
			const uint64_t d = (*depth_.index)[depth_.next].timestampNs;
			colourFirst = colour_.pass < depth_.pass || (colour_.pass == depth_.pass && c < d);
		}
		if (colourFirst)
			read(colour_, lock);
		else
			read(depth_, lock);
	}
}

// One frame into the lane's next slot, read without the lock.
template<typename Frame>
void ReplayPrefetch::read(Lane<Frame> &lane, std::unique_lock<std::mutex> &lock)
{
	using State = typename PrefetchedFrame<Frame>::State;
	PrefetchedFrame<Frame> &slot = lane.slots[lane.produced % kAhead];
	const size_t i = lane.next;
	const uint64_t generation = lane.generation;
	slot.state = State::Reading;
	lock.unlock();
	const int result = readFrame(i, slot.frame, slot.error);
	lock.lock();
	if (generation != lane.generation) { // restarted or stopped meanwhile
		slot.state = State::Free;
		return;
	}
	slot.index = i;
	slot.result = result;
	slot.generation = generation;
	slot.state = State::Ready;
	lane.produced++;
	if (result < 0)
		lane.refused[i] = true; // as the timeline will when it takes this slot
	lane.advance(loops_);
	const uint64_t one = 1;
	// A full counter (never: the loop reads it at every frame) is readable anyway.
	(void)!::write(eventFd_.get(), &one, sizeof(one));
}

int ReplayPrefetch::readFrame(size_t i, ColourFrame &frame, std::string &error)
{
	int ret = reader_->readColour(i, frame);
	// A sequence with mask/ is scored live as the simulator is (issue 29).
	if (ret >= 0 && reader_->hasMask())
		ret = reader_->readMask(i, frame.truth);
	else if (ret >= 0)
		frame.truth.resize(0, 0);
	if (ret < 0) {
		error = reader_->describeError();
		return ret;
	}
	const int width = frame.rgb.width(), height = frame.rgb.height();
	if (colourWidth_ > 0 && (width != colourWidth_ || height != colourHeight_)) {
		error = reader_->dir() + "/" + reader_->colour()[i].file + ": " + sizeText(width, height) +
			", not [colour]'s " + sizeText(colourWidth_, colourHeight_);
		return -EINVAL;
	}
	return 0;
}

int ReplayPrefetch::readFrame(size_t i, DepthFrame &frame, std::string &error)
{
	int ret = reader_->readDepth(i, frame);
	if (ret < 0)
		error = reader_->describeError();
	return ret;
}

void ReplayPrefetch::onReadable()
{
	uint64_t count;
	if (::read(eventFd_.get(), &count, sizeof(count)) < 0)
		return; // nothing new
	if (ready_)
		ready_();
}

} // namespace depthkey
