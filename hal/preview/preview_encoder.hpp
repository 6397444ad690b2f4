// The preview's JPEG worker: the event loop hands it copies of the stage
// images somebody watches; its own thread draws them (hal/preview/
// stage_picture.hpp) and encodes them with TurboJPEG; HTTP threads wait for
// the newest JPEG of a stage.
//
// Nothing here makes the pipeline wait: offer() only try-locks its stage's
// slot and skips the frame when the worker is taking the previous one, and
// the worker encodes whichever frame is newest when it gets to it (a slow
// encoder loses frames). A stage is copied and encoded only while an HTTP
// thread waits for its next JPEG: with no watcher, or only watchers that
// stopped reading (a client whose socket is full is not asked for more),
// wanted() is false and the event loop copies nothing: the frame cost is
// one atomic load per stage, and a stalled client costs no CPU.
#pragma once

#include "algo/image.hpp"
#include "algo/stage_images.hpp"
#include "hal/preview/preview_stages.hpp"

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <thread>

namespace depthkey {

struct PreviewEncoderStats {
	uint64_t encoded = 0;     // JPEGs made
	uint64_t skipped = 0;     // offers refused: the worker held the slot
	uint64_t encodeNs = 0;    // thread time spent drawing and encoding
	uint64_t failed = 0;      // encodes that failed
};

class PreviewEncoder
{
public:
	PreviewEncoder() = default;
	~PreviewEncoder() { stop(); }
	PreviewEncoder(const PreviewEncoder &) = delete;
	PreviewEncoder &operator=(const PreviewEncoder &) = delete;

	// quality 10..100; maxFps caps how often each stage is taken.
	int start(int quality, int maxFps);
	void stop();
	bool running() const { return thread_.joinable(); }

	// Event loop side. wanted(): somebody waits in waitNewer() for the
	// stage and its last copy is at least 1 / maxFps old (nowNs
	// CLOCK_MONOTONIC).
	bool wanted(PreviewStage stage, uint64_t nowNs) const;
	// The loop has the stage's picture at nowNs (told every frame, watched
	// or not: one atomic store): the stage's sign of life for making().
	void made(PreviewStage stage, uint64_t nowNs);
	// Copies the image into the stage's slot; false (frame skipped) when
	// the worker holds the slot. Never waits.
	bool offer(PreviewStage stage, const StageImage &image, uint64_t captureNs, uint64_t nowNs);
	// The same for a layer with its alpha (the lecturer layer), drawn over
	// a checkerboard (drawLayerPicture(), hal/preview/stage_picture.hpp).
	bool offer(PreviewStage stage, const RgbaImage &layer, uint64_t captureNs, uint64_t nowNs);

	// HTTP side. watch()/unwatch() count the clients of a stage (status
	// page); a client asks for frames by waiting in waitNewer().
	void watch(PreviewStage stage);
	void unwatch(PreviewStage stage);
	int watchers(PreviewStage stage) const;
	// The newest JPEG of the stage with a sequence above `after`, waiting
	// up to timeout; null on timeout or once stopped. While it waits
	// (timeout > 0) the stage is wanted.
	std::shared_ptr<const EncodedFrame> waitNewer(PreviewStage stage, uint64_t after,
						      std::chrono::milliseconds timeout);
	// The event loop told made() for the stage within the last
	// kMakingWindowNs: a client waiting for its next picture will get one. False for the depth, seeds and alpha of NO SIGNAL
	// (no cameras), which the server answers at once instead of letting a
	// tile wait seconds for nothing (issue 30).
	bool making(PreviewStage stage, uint64_t nowNs) const;
	static constexpr uint64_t kMakingWindowNs = 2'000'000'000u;
	PreviewEncoderStats stats() const;

private:
	struct Slot {
		std::mutex mutex;       // between offer() and the worker only
		bool fresh = false;
		StageKind kind = StageKind::Colour;
		RgbImage rgb;
		Gray16Image depth;
		Gray8Image gray;
		RgbaImage rgba;
		uint64_t captureNs = 0;
		std::atomic<int> watchers{ 0 };
		std::atomic<int> waiting{ 0 }; // threads inside waitNewer()
		std::atomic<uint64_t> lastOfferNs{ 0 };
		std::atomic<uint64_t> lastMadeNs{ 0 }; // made()'s last time, 0: never
		// The published JPEG, guarded by outMutex.
		std::mutex outMutex;
		std::condition_variable newFrame;
		std::shared_ptr<EncodedFrame> latest;
		uint64_t sequence = 0;
	};
	struct Work {
		StageKind kind = StageKind::Colour;
		RgbImage rgb;
		Gray16Image depth;
		Gray8Image gray;
		RgbaImage rgba;
		uint64_t captureNs = 0;
	};

	void run();
	// Under the slot's lock: stamps the offer and wakes the worker.
	void offered(Slot &slot, std::unique_lock<std::mutex> &lock, uint64_t captureNs, uint64_t nowNs);
	bool take(Slot &slot, Work &work);
	void encode(Slot &slot, const Work &work, class JpegEncoder &jpeg);

	std::array<Slot, kPreviewStageCount> slots_;
	std::thread thread_;
	std::mutex wakeMutex_;
	std::condition_variable wake_;
	std::atomic<bool> pending_{ false };
	std::atomic<bool> stopping_{ false };
	int quality_ = 80;
	uint64_t periodNs_ = 0;
	std::atomic<uint64_t> encoded_{ 0 }, skipped_{ 0 }, encodeNs_{ 0 }, failed_{ 0 };
};

} // namespace depthkey
