#include "hal/preview/preview_encoder.hpp"

#include "hal/preview/jpeg_encoder.hpp"
#include "hal/preview/stage_picture.hpp"

#include <pthread.h>
#include <ctime>

namespace depthkey {

namespace {

// The worker also wakes this often, so a missed notify costs at most this.
constexpr auto kIdleWake = std::chrono::milliseconds(50);

uint64_t threadCpuNs()
{
	timespec ts{};
	clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
	return static_cast<uint64_t>(ts.tv_sec) * 1'000'000'000u + static_cast<uint64_t>(ts.tv_nsec);
}

} // namespace

int PreviewEncoder::start(int quality, int maxFps)
{
	stop();
	quality_ = quality;
	periodNs_ = maxFps > 0 ? 1'000'000'000u / static_cast<uint64_t>(maxFps) : 0;
	stopping_ = false;
	thread_ = std::thread([this] { run(); });
	return 0;
}

void PreviewEncoder::stop()
{
	if (!thread_.joinable())
		return;
	stopping_ = true;
	wake_.notify_all();
	thread_.join();
	for (Slot &slot : slots_) {
		std::lock_guard lock(slot.outMutex);
		slot.newFrame.notify_all();
	}
}

bool PreviewEncoder::wanted(PreviewStage stage, uint64_t nowNs) const
{
	const Slot &slot = slots_[static_cast<size_t>(stage)];
	if (slot.waiting.load(std::memory_order_relaxed) == 0 || !thread_.joinable())
		return false;
	return nowNs - slot.lastOfferNs.load(std::memory_order_relaxed) >= periodNs_;
}

bool PreviewEncoder::offer(PreviewStage stage, const StageImage &image, uint64_t captureNs, uint64_t nowNs)
{
	Slot &slot = slots_[static_cast<size_t>(stage)];
	std::unique_lock lock(slot.mutex, std::try_to_lock);
	if (!lock.owns_lock()) {
		skipped_++;
		return false;
	}
	slot.kind = image.kind;
	// Same-size copies reuse the slot's buffers: no allocation once warm.
	if (image.rgb)
		slot.rgb = *image.rgb;
	if (image.depth)
		slot.depth = *image.depth;
	if (image.gray)
		slot.gray = *image.gray;
	if (!image.rgb)
		slot.rgb.resize(0, 0);
	if (!image.depth)
		slot.depth.resize(0, 0);
	if (!image.gray)
		slot.gray.resize(0, 0);
	slot.rgba.resize(0, 0);
	offered(slot, lock, captureNs, nowNs);
	return true;
}

bool PreviewEncoder::offer(PreviewStage stage, const RgbaImage &layer, uint64_t captureNs, uint64_t nowNs)
{
	Slot &slot = slots_[static_cast<size_t>(stage)];
	std::unique_lock lock(slot.mutex, std::try_to_lock);
	if (!lock.owns_lock()) {
		skipped_++;
		return false;
	}
	slot.kind = StageKind::Colour;
	slot.rgba = layer; // same size: the slot's buffer again
	slot.rgb.resize(0, 0);
	slot.depth.resize(0, 0);
	slot.gray.resize(0, 0);
	offered(slot, lock, captureNs, nowNs);
	return true;
}

void PreviewEncoder::offered(Slot &slot, std::unique_lock<std::mutex> &lock, uint64_t captureNs, uint64_t nowNs)
{
	slot.captureNs = captureNs;
	slot.fresh = true;
	lock.unlock();
	slot.lastOfferNs.store(nowNs, std::memory_order_relaxed);
	pending_ = true;
	wake_.notify_one();
}

void PreviewEncoder::watch(PreviewStage stage)
{
	slots_[static_cast<size_t>(stage)].watchers++;
}

void PreviewEncoder::unwatch(PreviewStage stage)
{
	slots_[static_cast<size_t>(stage)].watchers--;
}

int PreviewEncoder::watchers(PreviewStage stage) const
{
	return slots_[static_cast<size_t>(stage)].watchers.load();
}

std::shared_ptr<const EncodedFrame> PreviewEncoder::waitNewer(PreviewStage stage, uint64_t after,
							       std::chrono::milliseconds timeout)
{
	Slot &slot = slots_[static_cast<size_t>(stage)];
	std::unique_lock lock(slot.outMutex);
	if (timeout.count() > 0 && !stopping_ && slot.sequence <= after) {
		slot.waiting++;
		slot.newFrame.wait_for(lock, timeout, [&] { return stopping_ || slot.sequence > after; });
		slot.waiting--;
	}
	if (stopping_ || slot.sequence <= after)
		return nullptr;
	return slot.latest;
}

void PreviewEncoder::made(PreviewStage stage, uint64_t nowNs)
{
	slots_[static_cast<size_t>(stage)].lastMadeNs.store(nowNs, std::memory_order_relaxed);
}

bool PreviewEncoder::making(PreviewStage stage, uint64_t nowNs) const
{
	const uint64_t made = slots_[static_cast<size_t>(stage)].lastMadeNs.load(std::memory_order_relaxed);
	// The loop's clock read may come just after the caller's.
	return made != 0 && (made >= nowNs || nowNs - made < kMakingWindowNs);
}

PreviewEncoderStats PreviewEncoder::stats() const
{
	return { encoded_.load(), skipped_.load(), encodeNs_.load(), failed_.load() };
}

// Swaps the slot's images with the worker's: O(1) under the lock, so that
// offer() almost never finds it taken.
bool PreviewEncoder::take(Slot &slot, Work &work)
{
	std::lock_guard lock(slot.mutex);
	if (!slot.fresh)
		return false;
	std::swap(slot.rgb, work.rgb);
	std::swap(slot.depth, work.depth);
	std::swap(slot.gray, work.gray);
	std::swap(slot.rgba, work.rgba);
	work.kind = slot.kind;
	work.captureNs = slot.captureNs;
	slot.fresh = false;
	return true;
}

void PreviewEncoder::encode(Slot &slot, const Work &work, JpegEncoder &jpeg)
{
	StageImage stage{ "", work.kind, work.rgb.empty() ? nullptr : &work.rgb,
			  work.depth.empty() ? nullptr : &work.depth, work.gray.empty() ? nullptr : &work.gray };
	const StagePicture picture = work.rgba.empty() ? drawStagePicture(stage) : drawLayerPicture(work.rgba);
	if (picture.empty())
		return;
	// A new buffer per JPEG (on this thread, at most max_fps per stage):
	// HTTP threads may still be sending the previous one.
	auto frame = std::make_shared<EncodedFrame>();
	const bool grey = picture.rgb.empty();
	const uint8_t *data = grey ? picture.gray.data() : reinterpret_cast<const uint8_t *>(picture.rgb.data());
	const int stride = picture.width() * (grey ? 1 : 3);
	if (jpeg.encode(data, picture.width(), picture.height(), stride, grey ? JpegPixels::Gray : JpegPixels::Rgb,
			quality_, frame->jpeg) < 0) {
		failed_++;
		return;
	}
	frame->captureNs = work.captureNs;
	frame->width = picture.width();
	frame->height = picture.height();
	{
		std::lock_guard lock(slot.outMutex);
		frame->sequence = ++slot.sequence;
		slot.latest = std::move(frame);
	}
	slot.newFrame.notify_all();
	encoded_++;
}

void PreviewEncoder::run()
{
	pthread_setname_np(pthread_self(), "dk-preview"); // for top -H and make bench-process
	JpegEncoder jpeg;
	Work work;
	while (!stopping_) {
		{
			std::unique_lock lock(wakeMutex_);
			wake_.wait_for(lock, kIdleWake, [this] { return stopping_ || pending_; });
		}
		pending_ = false;
		for (Slot &slot : slots_) {
			if (stopping_ || !take(slot, work))
				continue;
			uint64_t t0 = threadCpuNs();
			encode(slot, work, jpeg);
			encodeNs_ += threadCpuNs() - t0;
		}
	}
}

} // namespace depthkey
