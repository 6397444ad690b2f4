// Per-frame cost of the virtual webcam (output.v4l2_device) on the event
// loop: BM_WebcamConvert the RGB -> YUYV conversion alone (C row: sse2:0,
// best row, SSE2 or on arm64 NEON: sse2:1),
// BM_WebcamWrite all of V4l2Output::write() into a device that copies the
// frame as v4l2loopback's write() does (copy_from_user into its buffer),
// i.e. what the daemon pays per published frame with the webcam on. With
// output.v4l2_device = "" the daemon pays one call that returns at once.
#include "hal/event_loop.hpp"
#include "hal/v4l2/rgb_to_yuyv.hpp"
#include "hal/v4l2/v4l2_output.hpp"

#include <benchmark/benchmark.h>

#include <cstring>
#include <vector>

using namespace depthkey;

namespace {

RgbImage picture(int w, int h)
{
	RgbImage image(w, h);
	for (int y = 0; y < h; ++y)
		for (int x = 0; x < w; ++x)
			image.at(x, y) = { static_cast<uint8_t>(x * 7), static_cast<uint8_t>(y * 3),
					   static_cast<uint8_t>(x + y) };
	return image;
}

// Takes each frame the way v4l2loopback does: one copy into its buffer.
class CopyingDevice : public VideoOutputDevice
{
public:
	int open(const std::string &, int, int, size_t frameBytes, std::string &) override
	{
		buffer_.resize(frameBytes);
		return 0;
	}
	ssize_t write(const uint8_t *data, size_t bytes) override
	{
		std::memcpy(buffer_.data(), data, bytes);
		benchmark::ClobberMemory();
		return static_cast<ssize_t>(bytes);
	}
	void close() override {}

private:
	std::vector<uint8_t> buffer_;
};

void BM_WebcamConvert(benchmark::State &state)
{
	const int w = static_cast<int>(state.range(0)), h = static_cast<int>(state.range(1));
	RgbImage image = picture(w, h);
	std::vector<uint8_t> yuyv(yuyvFrameBytes(w, h));
	for (auto _ : state) {
		rgbToYuyv(image, yuyv.data(), yuyv.size(), state.range(2) ? bestKernelPath() : KernelPath::C);
		benchmark::DoNotOptimize(yuyv.data());
	}
	state.SetItemsProcessed(state.iterations() * w * h);
}

void BM_WebcamWrite(benchmark::State &state)
{
	const int w = static_cast<int>(state.range(0)), h = static_cast<int>(state.range(1));
	RgbImage image = picture(w, h);
	EventLoop loop;
	loop.open();
	V4l2Output output(std::make_unique<CopyingDevice>());
	output.setKernelPath(state.range(2) ? bestKernelPath() : KernelPath::C);
	output.start(loop, "/dev/video10", nullptr);
	output.write(image); // opens
	for (auto _ : state)
		benchmark::DoNotOptimize(output.write(image));
	state.SetItemsProcessed(state.iterations() * w * h);
}

void BM_WebcamOff(benchmark::State &state)
{
	RgbImage image = picture(640, 480);
	EventLoop loop;
	loop.open();
	V4l2Output output;
	output.start(loop, "", nullptr);
	for (auto _ : state)
		benchmark::DoNotOptimize(output.write(image));
}

} // namespace

#define SIZES_AND_PATHS                                                                                  \
	->Args({ 640, 480, 0 })->Args({ 640, 480, 1 })->Args({ 1920, 1080, 0 })->Args({ 1920, 1080, 1 }) \
	->ArgNames({ "w", "h", "sse2" })->Unit(benchmark::kMicrosecond)
BENCHMARK(BM_WebcamConvert) SIZES_AND_PATHS;
BENCHMARK(BM_WebcamWrite) SIZES_AND_PATHS;
BENCHMARK(BM_WebcamOff)->Unit(benchmark::kNanosecond);
