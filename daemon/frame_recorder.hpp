// Records the frames the daemon receives into a sequence folder
// (hal/recording/sequence_format.hpp) without stalling the event loop:
// PNG encoding (several ms for a 640x480 frame) runs on one worker thread.
// The loop thread only copies the frame into a free pre-allocated slot; when
// the worker falls behind and no slot is free, the frame is dropped and
// counted (a recording with gaps, never a late daemon).
#pragma once

#include "algo/frames.hpp"
#include "hal/recording/sequence_writer.hpp"

#include <array>
#include <atomic>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

namespace depthkey {

class FrameRecorder
{
public:
	FrameRecorder() = default;
	~FrameRecorder() { stop(); }
	FrameRecorder(const FrameRecorder &) = delete;
	FrameRecorder &operator=(const FrameRecorder &) = delete;

	// Creates the folder and starts the worker. Colour frames are to be
	// colourWidth x colourHeight (0: any): a folder of another size is left
	// for dir/WxH (SequenceWriter::open). Negative errno; error says what
	// and where.
	int start(const std::string &dir, int pngCompression, std::string &error, int colourWidth = 0,
		  int colourHeight = 0);
	// Writes what is queued, then stops the worker.
	void stop();
	bool running() const { return worker_.joinable(); }
	// The folder frames go to: the one start() was given, or a session
	// folder inside it (SequenceWriter::open).
	const std::string &dir() const { return dir_; }

	void recordColour(const ColourFrame &frame);
	void recordDepth(const DepthFrame &frame);

	uint64_t written() const { return written_; }
	uint64_t dropped() const { return dropped_; }
	// The worker's latest write error, "" if none since the last call.
	std::string takeError();

private:
	static constexpr int kColourSlots = 6;  // ~0.25 s of colour at 25 fps
	static constexpr int kDepthSlots = 3;
	static constexpr int kJobs = kColourSlots + kDepthSlots;
	struct Job {
		bool colour;
		int slot;
	};
	template<typename Frame, size_t N>
	void enqueue(const Frame &frame, std::array<Frame, N> &slots, std::array<bool, N> &busy, bool colour);
	void run();

	std::string dir_;
	SequenceWriter writer_;
	std::thread worker_;
	std::mutex mutex_;
	std::condition_variable wake_;
	bool stopping_ = false;
	std::array<ColourFrame, kColourSlots> colour_;
	std::array<DepthFrame, kDepthSlots> depth_;
	std::array<bool, kColourSlots> colourBusy_{};
	std::array<bool, kDepthSlots> depthBusy_{};
	std::array<Job, kJobs> jobs_{};
	int jobHead_ = 0, jobCount_ = 0;
	std::string error_;
	std::atomic<uint64_t> written_{ 0 }, dropped_{ 0 };
};

} // namespace depthkey
