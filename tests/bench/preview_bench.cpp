// What the live preview costs: one JPEG of a 640x480 stage on the preview's
// worker thread (drawn and encoded as the page gets it), the event loop's
// copy of a watched stage, and the per-frame check when nobody watches (the
// daemon's frame cost without a client).
#include "daemon/preview_feed.hpp"
#include "hal/preview/jpeg_encoder.hpp"
#include "hal/preview/stage_picture.hpp"
#include "hal/sim/lecture_simulator.hpp"

#include <benchmark/benchmark.h>

#include <atomic>
#include <thread>

using namespace depthkey;

namespace {

ColourFrame simulatedColour()
{
	LectureSimulator sim;
	sim.configure(SimSettings{}, 640, 480);
	ColourFrame frame;
	sim.renderColour(3.0, frame, nullptr);
	return frame;
}

// range(0): 0 = the colour/composite picture (4:2:0), 1 = the alpha matte (grey).
void BM_PreviewJpeg640x480(benchmark::State &state)
{
	const ColourFrame frame = simulatedColour();
	Gray8Image alpha(640, 480, 0);
	for (int y = 120; y < 420; y++)
		for (int x = 250; x < 390; x++)
			alpha.at(x, y) = 255;
	const bool grey = state.range(0) != 0;
	StageImage stage{ "", grey ? StageKind::Mask : StageKind::Colour, grey ? nullptr : &frame.rgb, nullptr,
			  grey ? &alpha : nullptr };
	JpegEncoder jpeg;
	std::vector<uint8_t> out;
	for (auto _ : state) {
		StagePicture picture = drawStagePicture(stage);
		if (grey)
			jpeg.encode(picture.gray.data(), picture.width(), picture.height(), picture.width(), JpegPixels::Gray,
				    80, out);
		else
			jpeg.encode(reinterpret_cast<const uint8_t *>(picture.rgb.data()), picture.width(), picture.height(), picture.width() * 3,
				    JpegPixels::Rgb, 80, out);
		benchmark::DoNotOptimize(out.data());
	}
	state.counters["jpeg_bytes"] = static_cast<double>(out.size());
}
BENCHMARK(BM_PreviewJpeg640x480)->Arg(0)->Arg(1)->ArgName("grey")->Unit(benchmark::kMillisecond);

// The event loop's side per frame: range(0) = 0 nobody waits for a JPEG
// (five atomic loads), 1 a client waits for the composite (one 640x480 copy
// into its slot).
void BM_PreviewOffer(benchmark::State &state)
{
	PreviewEncoder encoder;
	encoder.start(80, 1000000); // no frame cap: every offer copies
	std::atomic<bool> done{ false };
	std::thread client;
	if (state.range(0))
		client = std::thread([&] {
			uint64_t seen = 0;
			while (!done)
				if (auto frame = encoder.waitNewer(PreviewStage::Composite, seen,
								   std::chrono::milliseconds(100)))
					seen = frame->sequence;
		});
	const ColourFrame frame = simulatedColour();
	StageImage stage{ "", StageKind::Colour, &frame.rgb };
	uint64_t now = 1'000'000'000u;
	for (auto _ : state) {
		now += 40'000'000u;
		for (size_t s = 0; s < kPreviewStageCount; s++) {
			encoder.made(static_cast<PreviewStage>(s), now); // as daemon/preview_feed.cpp does
			if (encoder.wanted(static_cast<PreviewStage>(s), now))
				encoder.offer(static_cast<PreviewStage>(s), stage, now, now);
		}
	}
	done = true;
	if (client.joinable())
		client.join();
	encoder.stop();
}
BENCHMARK(BM_PreviewOffer)->Arg(0)->Arg(1)->ArgName("watched")->Unit(benchmark::kMicrosecond);

} // namespace
