// Per-frame cost of the composite and lecturer-layer kernels at the colour
// resolutions the box supports.
#include "algo/composite.hpp"

#include <benchmark/benchmark.h>

using namespace depthkey;

namespace {

void BM_Composite(benchmark::State &state)
{
	const int w = static_cast<int>(state.range(0)), h = static_cast<int>(state.range(1));
	RgbImage colour(w, h, Rgb8{ 200, 120, 80 }), board(w, h, Rgb8{ 30, 60, 40 }), out(w, h);
	Gray8Image alpha(w, h);
	for (size_t i = 0; i < alpha.size(); ++i)
		alpha.data()[i] = static_cast<uint8_t>(i * 7);
	for (auto _ : state) {
		composite(colour, alpha, board, 128, out);
		benchmark::DoNotOptimize(out.data());
	}
	state.SetItemsProcessed(state.iterations() * w * h);
}

void BM_LecturerLayer(benchmark::State &state)
{
	const int w = static_cast<int>(state.range(0)), h = static_cast<int>(state.range(1));
	RgbImage colour(w, h, Rgb8{ 200, 120, 80 });
	Gray8Image alpha(w, h, 255);
	RgbaImage out(w, h);
	for (auto _ : state) {
		lecturerLayer(colour, alpha, out);
		benchmark::DoNotOptimize(out.data());
	}
	state.SetItemsProcessed(state.iterations() * w * h);
}

} // namespace

BENCHMARK(BM_Composite)->Args({ 640, 480 })->Args({ 1920, 1080 })->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_LecturerLayer)->Args({ 640, 480 })->Args({ 1920, 1080 })->Unit(benchmark::kMicrosecond);
