// The simulator runs inside depthkeyd (25 fps colour + 10 fps depth on the
// core the pipeline uses), and the recorder encodes PNGs on its thread:
// what each costs per frame.
#include "hal/recording/sequence_writer.hpp"
#include "hal/sim/lecture_simulator.hpp"

#include <benchmark/benchmark.h>
#include <opencv2/imgcodecs.hpp>
#include <vector>

using namespace depthkey;

namespace {

// Time advances by a frame each iteration so the lecturer moves and the
// board content changes as in the daemon.
void BM_SimRenderColour(benchmark::State &state)
{
	LectureSimulator sim;
	sim.configure(SimSettings{}, static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
	ColourFrame frame;
	GroundTruth truth;
	const bool withTruth = state.range(2) != 0;
	double t = 0.5;
	sim.renderColour(t, frame, withTruth ? &truth : nullptr); // tables built once, outside the timing
	for (auto _ : state) {
		t += 0.04;
		if (t > 27)
			t = 0.5;
		sim.renderColour(t, frame, withTruth ? &truth : nullptr);
		benchmark::DoNotOptimize(frame.rgb.data());
	}
}
BENCHMARK(BM_SimRenderColour)->Args({ 640, 480, 0 })->Args({ 640, 480, 1 })->Args({ 1280, 720, 0 })
	->Unit(benchmark::kMillisecond);

void BM_SimRenderDepth(benchmark::State &state)
{
	LectureSimulator sim;
	SimSettings settings;
	settings.motionBlur = state.range(0) != 0;
	sim.configure(settings, 640, 480);
	DepthFrame frame;
	double t = 0.5;
	sim.renderDepth(t, frame);
	for (auto _ : state) {
		t += 0.1;
		if (t > 27)
			t = 0.5;
		sim.renderDepth(t, frame);
		benchmark::DoNotOptimize(frame.depthMm.data());
	}
}
BENCHMARK(BM_SimRenderDepth)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond);

// PNG encoding of one 640x480 colour frame at a zlib level: the recorder's
// cost per frame (it uses level 1).
void encodePng(benchmark::State &state, const cv::Mat &image, int level)
{
	std::vector<uchar> png;
	const std::vector<int> params = { cv::IMWRITE_PNG_COMPRESSION, level };
	for (auto _ : state) {
		cv::imencode(".png", image, png, params);
		benchmark::DoNotOptimize(png.data());
	}
	state.counters["bytes"] = static_cast<double>(png.size());
}

void BM_PngEncodeColour640x480(benchmark::State &state)
{
	LectureSimulator sim;
	sim.configure(SimSettings{}, 640, 480);
	ColourFrame frame;
	sim.renderColour(3.0, frame);
	encodePng(state, cv::Mat(480, 640, CV_8UC3, frame.rgb.data()), static_cast<int>(state.range(0)));
}
BENCHMARK(BM_PngEncodeColour640x480)->Arg(0)->Arg(1)->Arg(3)->Arg(6)->Unit(benchmark::kMillisecond);

void BM_PngEncodeDepth160x124(benchmark::State &state)
{
	LectureSimulator sim;
	sim.configure(SimSettings{}, 640, 480);
	DepthFrame frame;
	sim.renderDepth(3.0, frame);
	encodePng(state, cv::Mat(124, 160, CV_16UC1, frame.depthMm.data()), 1);
}
BENCHMARK(BM_PngEncodeDepth160x124)->Unit(benchmark::kMillisecond);

} // namespace
