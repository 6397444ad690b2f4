// Per-frame cost of the composite and lecturer-layer kernels over whole
// frames at the colour resolutions the box supports, C rows (path 0) against
// the best rows this build has (path 1: SSE2 on x86-64, NEON on arm64). The matte is a lecturer-like blob with a soft edge.
#include "algo/composite.hpp"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>

using namespace depthkey;

namespace {

// An ellipse of 255 in the middle third, 0 around, a 3 px ramp on its edge.
Gray8Image blobMatte(int w, int h)
{
	Gray8Image alpha(w, h);
	for (int y = 0; y < h; ++y) {
		for (int x = 0; x < w; ++x) {
			double dx = (x - w / 2.0) / (w / 6.0), dy = (y - h / 2.0) / (h / 3.0);
			double inside = (1.0 - std::sqrt(dx * dx + dy * dy)) * (w / 6.0) / 3.0;
			alpha.at(x, y) = static_cast<uint8_t>(std::clamp(inside, 0.0, 1.0) * 255.0);
		}
	}
	return alpha;
}

void BM_Composite(benchmark::State &state)
{
	const int w = static_cast<int>(state.range(0)), h = static_cast<int>(state.range(1));
	RgbImage colour(w, h, Rgb8{ 200, 120, 80 }), board(w, h, Rgb8{ 30, 60, 40 }), out(w, h);
	Gray8Image alpha = blobMatte(w, h);
	const KernelPath path = state.range(2) ? bestKernelPath() : KernelPath::C;
	for (auto _ : state) {
		composite(colour, alpha, board, 128, out, path);
		benchmark::DoNotOptimize(out.data());
	}
	state.SetItemsProcessed(state.iterations() * w * h);
}

void BM_LecturerLayer(benchmark::State &state)
{
	const int w = static_cast<int>(state.range(0)), h = static_cast<int>(state.range(1));
	RgbImage colour(w, h, Rgb8{ 200, 120, 80 });
	Gray8Image alpha = blobMatte(w, h);
	RgbaImage out(w, h);
	const KernelPath path = state.range(2) ? bestKernelPath() : KernelPath::C;
	for (auto _ : state) {
		lecturerLayer(colour, alpha, out, path);
		benchmark::DoNotOptimize(out.data());
	}
	state.SetItemsProcessed(state.iterations() * w * h);
}

} // namespace

#define SIZES_AND_PATHS                                                                      \
	->Args({ 640, 480, 0 })->Args({ 640, 480, 1 })->Args({ 1920, 1080, 0 })->Args({ 1920, 1080, 1 }) \
	->ArgNames({ "w", "h", "sse2" })->Unit(benchmark::kMicrosecond)
BENCHMARK(BM_Composite) SIZES_AND_PATHS;
BENCHMARK(BM_LecturerLayer) SIZES_AND_PATHS;
