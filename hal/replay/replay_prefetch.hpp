// A replay's frames read and decoded ahead of play, on a thread of its own
// ("dk-replay"), so that the event loop's timer only hands a decoded frame
// over (issue 29 §2). A camera on the box delivers raw frames by DMA; the
// PNG decoding is the stand-in's cost, not the box's: on its own thread it
// can be kept out of a CPU share that models the box, and it no longer
// holds the loop up (it was half of the loop's time at 640x480).
//
// Each stream (colour, depth) is a lane of kAhead slots, a ring the thread
// fills in the order the timeline plays them: index 0 onwards, from 0 again
// after the last when the replay loops, skipping the frames refused (a
// timestamp repeated, or found bad on an earlier pass). A frame that cannot
// be read is handed over too, with its error, and the thread refuses it
// from then on, as the timeline does when it takes it: both walk the same
// indices. The slots' frames keep their storage: no allocation per frame
// once the first frames have sized them, and never more than kAhead frames
// of a stream in memory (a 1920x1080 colour frame is 6 MB).
//
// Ownership: a slot is the thread's while Free or Reading, the loop's while
// Ready or Held; the state changes under one mutex (happens-before both
// ways). The SequenceReader is shared: the thread reads images with it, the
// loop only its index, which open() changes only while the thread is
// stopped.
#pragma once

#include "algo/frames.hpp"
#include "hal/event_loop.hpp"
#include "hal/recording/sequence_reader.hpp"
#include "hal/unique_fd.hpp"

#include <array>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace depthkey {

// One frame read ahead: its pixels, or why it cannot be played.
template<typename Frame>
struct PrefetchedFrame {
	enum class State { Free, Reading, Ready, Held };
	State state = State::Free;
	uint64_t generation = 0; // the lane's when it was read
	size_t index = 0;        // in the stream's index
	int result = 0;          // 0, or a negative errno
	std::string error;       // what and where, when result < 0
	Frame frame;
};

class ReplayPrefetch
{
public:
	// Frames read ahead per stream: 3 colour frames cover 120 ms at 25 fps,
	// several decodes' worth of a late reader.
	static constexpr size_t kAhead = 3;

	ReplayPrefetch() = default;
	~ReplayPrefetch() { stop(); }
	ReplayPrefetch(const ReplayPrefetch &) = delete;
	ReplayPrefetch &operator=(const ReplayPrefetch &) = delete;

	// Starts the thread, every lane idle until restart(). A colour frame is
	// read only at colourWidth x colourHeight (0 x 0: any size). ready() runs
	// on the loop when a frame has been read. A negative errno when the
	// eventfd, its loop source or the thread cannot be had.
	int start(EventLoop &loop, SequenceReader &reader, int colourWidth, int colourHeight, bool loops,
		  std::function<void()> ready);
	// Joins the thread (a read in progress is finished first: one decode)
	// and forgets what was read. Safe to call twice.
	void stop();
	bool running() const { return thread_.joinable(); }

	// Loop only. The stream's frames from index 0 on, skipping those marked
	// in refused; what was read before is dropped.
	template<typename Frame>
	void restart(const std::vector<bool> &refused);
	// Loop only: the stream is not played; nothing more is read for it.
	template<typename Frame>
	void idle();
	// Loop only: the next frame of the stream once read, else null (ready()
	// runs when it is). The loop holds it until release().
	template<typename Frame>
	PrefetchedFrame<Frame> *take();
	// Loop only: the slot goes back to the thread. After a restart() or a
	// stop() in between it is only freed.
	template<typename Frame>
	void release(PrefetchedFrame<Frame> *frame);

private:
	template<typename Frame>
	struct Lane {
		std::array<PrefetchedFrame<Frame>, kAhead> slots;
		const std::vector<SequenceEntry> *index = nullptr;
		std::vector<bool> refused; // the thread's view: as the timeline's at the same index
		uint64_t generation = 0;   // bumped by restart/idle/stop: reads in flight are dropped
		uint64_t produced = 0, consumed = 0;
		size_t next = 0;      // the index the thread reads next
		uint64_t pass = 0;    // times round the recording (loop = true)
		bool active = false;  // restarted and not yet at its end

		void reset(uint64_t newGeneration);
		void advance(bool loops);
		bool wantsRead() const;
	};
	template<typename Frame>
	Lane<Frame> &lane();
	template<typename Frame>
	void read(Lane<Frame> &lane, std::unique_lock<std::mutex> &lock);
	int readFrame(size_t i, ColourFrame &frame, std::string &error);
	int readFrame(size_t i, DepthFrame &frame, std::string &error);
	void run();
	void onReadable();

	SequenceReader *reader_ = nullptr;
	int colourWidth_ = 0, colourHeight_ = 0;
	bool loops_ = false;
	std::function<void()> ready_;
	UniqueFd eventFd_; // declared before source_: closed after it leaves the loop
	EventSource source_;
	std::thread thread_;

	std::mutex mutex_;
	std::condition_variable wake_; // a slot freed, a lane restarted, stop
	bool stop_ = false;
	uint64_t generations_ = 0; // never reused: a slot held across stop/start stays stale
	Lane<ColourFrame> colour_;
	Lane<DepthFrame> depth_;
};

} // namespace depthkey
