// Per-frame cost of the board-geometry output (algo/board_compositor.hpp):
// the lecturer's colour and alpha warped into a 1920x1080 board picture and
// blended, plus the board-geometry lecturer layer, from a 640x480 colour
// frame of the simulated lecture with its true alpha and ROI (the lecturer
// in the middle, talking, and at the board, writing). Beside it the
// camera-geometry composite + layer of the same frame (compositeRoi +
// lecturerLayer at 640x480), what the daemon publishes without H; and the
// upper bound, alpha everywhere (the whole colour frame warped), and the
// floor, nobody there (the board picture copied). And the board-geometry
// frame published to the shared memory (BM_BoardPublish): made in images
// and copied into the ring, or made in the ring's slots (issue 29 §2).
#include "algo/board_compositor.hpp"
#include "algo/composite.hpp"
#include "hal/kernel_path_env.hpp"
#include "hal/shm_frame_sink.hpp"
#include "hal/sim/board_display.hpp"
#include "hal/sim/lecture_simulator.hpp"

#include <benchmark/benchmark.h>

#include <string>
#include <unistd.h>

using namespace depthkey;

namespace {

constexpr int kBoardW = 1920, kBoardH = 1080;

struct Frame {
	ColourFrame colour;
	GroundTruth truth;
	Roi roi;
	RgbImage board;
	Homography colourToBoard;
};

Frame lectureFrame(double timeS)
{
	Frame f;
	LectureSimulator sim;
	sim.configure(SimSettings{}, 640, 480);
	sim.renderColour(timeS, f.colour, &f.truth);
	f.roi = { 640, 480, 0, 0 };
	for (int y = 0; y < 480; ++y)
		for (int x = 0; x < 640; ++x)
			if (f.truth.alpha.at(x, y))
				f.roi = { std::min(f.roi.x0, x), std::min(f.roi.y0, y), std::max(f.roi.x1, x + 1),
					  std::max(f.roi.y1, y + 1) };
	// The simulated board shown at 1920x1080: its H, scaled.
	const int simH = simBoardHeight(kBoardW);
	f.colourToBoard = simTrueHomography(sim.rig(), 2.0, kBoardW, simH).then(boardScaling(kBoardW, simH, kBoardW, kBoardH));
	SimBoardDisplay display;
	display.configure(SimSettings{}, kBoardW);
	RgbImage picture;
	display.render(timeS, picture);
	f.board.resize(kBoardW, kBoardH);
	for (int y = 0; y < kBoardH; ++y)
		for (int x = 0; x < kBoardW; ++x)
			f.board.at(x, y) = picture.at(x, y * simH / kBoardH);
	return f;
}

// range(0): scene time (s) of the frame; range(1): 1 = the whole frame opaque,
// 2 = an empty ROI (the cost of the board copy alone), 3 = this frame and the
// next (40 ms on) in turn, so that the layer is cleared where he no longer
// is (the other cases repeat one frame: nothing to clear), 4 = as 3, with a
// new board picture every frame (a capture stick's: the board copied whole,
// not only where he was). range(2): which rows, 0 = the best this CPU has
// (DEPTHKEY_FORCE_C: the C rows), 1 = the SSE2 rows, 2 = the SSSE3 rows
// (what the better ones save).
void BM_BoardWarpComposite(benchmark::State &state)
{
	constexpr double kFrameS = 0.04;
	Frame f = lectureFrame(double(state.range(0)));
	Gray8Image alpha = f.truth.alpha;
	Roi roi = f.roi;
	if (state.range(1) == 1) {
		alpha = Gray8Image(640, 480, 255);
		roi = { 0, 0, 640, 480 };
	} else if (state.range(1) == 2) {
		roi = {}; // nobody there: the board picture copied, nothing warped
	}
	BoardCompositor compositor;
	compositor.configure(f.colourToBoard, 640, 480, kBoardW, kBoardH);
	const KernelPath rows[] = { kernelPathFromEnvironment(), KernelPath::Sse2, KernelPath::Ssse3 };
	compositor.setKernelPath(rows[state.range(2)]);
	RgbImage composite;
	RgbaImage layer, cameraLayer[2];
	Roi rois[2] = { roi, roi };
	lecturerLayer(f.colour.rgb, alpha, cameraLayer[0]); // the pipeline's output, its input
	cameraLayer[1] = cameraLayer[0];
	if (state.range(1) >= 3) {
		const Frame next = lectureFrame(double(state.range(0)) + kFrameS);
		lecturerLayer(next.colour.rgb, next.truth.alpha, cameraLayer[1]);
		rois[1] = next.roi;
	}
	size_t frame = 0;
	for (auto _ : state) {
		const size_t i = frame++ % 2;
		if (state.range(1) == 4)
			compositor.forgetBoard();
		compositor.compose(cameraLayer[i], rois[i], f.board, 128, composite, layer);
		benchmark::DoNotOptimize(composite.data());
		benchmark::ClobberMemory();
	}
	const Roi &w = compositor.warpedRoi();
	state.counters["roi_px"] = double(w.x1 - w.x0) * (w.y1 - w.y0);
	state.counters["warped_px"] = double(compositor.warpedPixels());
}

// The composite and the board-geometry layer to the shared memory (2
// slots, the default), this frame and the next in turn (whole:3 above).
// range(1): 0 = composed into images, then copied into the slots
// (publishComposite + publishBoardLecturer); 1 = composed in the slots
// (publishBoard); range(2): 1 = a new board picture every 5th frame.
void BM_BoardPublish(benchmark::State &state)
{
	constexpr double kFrameS = 0.04;
	const Frame f = lectureFrame(double(state.range(0)));
	const Frame next = lectureFrame(double(state.range(0)) + kFrameS);
	BoardCompositor compositor;
	compositor.configure(f.colourToBoard, 640, 480, kBoardW, kBoardH);
	RgbaImage cameraLayer[2];
	lecturerLayer(f.colour.rgb, f.truth.alpha, cameraLayer[0]);
	lecturerLayer(next.colour.rgb, next.truth.alpha, cameraLayer[1]);
	const Roi rois[2] = { f.roi, next.roi };
	const std::string prefix = "/depthkey-bench-" + std::to_string(getpid());
	OutputSettings names;
	names.compositeName = prefix + ".composite";
	names.lecturerName = prefix + ".lecturer";
	names.boardLecturerName = prefix + ".lecturer.board";
	ShmFrameSink sink;
	if (sink.open(names, 640, 480, kBoardW, kBoardH) < 0) {
		state.SkipWithError(sink.describeError().c_str());
		return;
	}
	ComposedBoardFrame maker;
	maker.compositor = &compositor;
	maker.board = &f.board;
	maker.opacityQ8 = 128;
	RgbImage composite;
	RgbaImage layer;
	size_t frame = 0;
	for (auto _ : state) {
		const size_t i = frame % 2;
		if (state.range(2) && frame % 5 == 0)
			compositor.forgetBoard();
		frame++;
		if (state.range(1)) {
			maker.layer = &cameraLayer[i];
			maker.roi = rois[i];
			sink.publishBoard(maker, frame, 0);
		} else {
			compositor.compose(cameraLayer[i], rois[i], f.board, 128, composite, layer);
			sink.publishComposite(composite, frame, 0);
			sink.publishBoardLecturer(layer, frame, 0);
		}
	}
	sink.remove();
}

void BM_CameraGeometryComposite(benchmark::State &state)
{
	Frame f = lectureFrame(double(state.range(0)));
	RgbImage board(640, 480, Rgb8{ 30, 60, 40 }), composite;
	RgbaImage layer;
	const KernelPath path = kernelPathFromEnvironment();
	for (auto _ : state) {
		compositeRoi(f.colour.rgb, f.truth.alpha, board, f.roi, 128, composite, path);
		lecturerLayer(f.colour.rgb, f.truth.alpha, layer, path);
		benchmark::DoNotOptimize(composite.data());
		benchmark::ClobberMemory();
	}
}

} // namespace

// 1 s: talking in the middle of the room; 8 s: writing at the board.
BENCHMARK(BM_BoardWarpComposite)
	->Args({ 1, 0, 0 })
	->Args({ 1, 0, 1 })
	->Args({ 1, 0, 2 })
	->Args({ 1, 3, 0 })
	->Args({ 1, 4, 0 })
	->Args({ 1, 4, 2 })
	->Args({ 8, 0, 0 })
	->Args({ 8, 3, 0 })
	->Args({ 8, 4, 0 })
	->Args({ 8, 1, 0 })
	->Args({ 8, 2, 0 })
	->ArgNames({ "t", "whole", "rows" })
	->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_BoardPublish)
	->Args({ 1, 0, 0 })
	->Args({ 1, 1, 0 })
	->Args({ 1, 0, 1 })
	->Args({ 1, 1, 1 })
	->Args({ 8, 0, 0 })
	->Args({ 8, 1, 0 })
	->ArgNames({ "t", "in_slots", "new_board" })
	->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_CameraGeometryComposite)->Args({ 1 })->Args({ 8 })->ArgNames({ "t" })->Unit(benchmark::kMicrosecond);
