// The depth-offset estimator (algo/latency_estimator.hpp) runs on the event
// loop: per colour frame a sparse luma grid, per depth frame its 4x4 blocks
// and the fold of one interval into the per-lag sums, once a second an
// estimate. What one second of the streams costs at 640x480 25 fps colour
// and the simulated ToF at 10 fps (issue 29 §3).
#include "algo/latency_estimator.hpp"
#include "hal/sim/lecture_simulator.hpp"
#include "settings/settings.hpp"

#include <benchmark/benchmark.h>

#include <array>

using namespace depthkey;

namespace {

void BM_LatencyEstimatorSecond(benchmark::State &state)
{
	// A few frames of the lecture, rendered outside the timing and fed in
	// turn with advancing timestamps (the cost does not depend on what
	// moved).
	LectureSimulator sim;
	sim.configure(SimSettings{}, 640, 480);
	std::array<ColourFrame, 4> colour;
	std::array<DepthFrame, 4> depth;
	for (size_t k = 0; k < colour.size(); ++k) {
		sim.renderColour(3.0 + 0.04 * double(k), colour[k], nullptr);
		sim.renderDepth(3.0 + 0.1 * double(k), depth[k]);
	}
	SegmentationSettings segmentation;
	LatencyEstimator estimator;
	estimator.configure(segmentation.nearMm, segmentation.farMm);
	uint64_t ns = 0;
	size_t n = 0;
	for (auto _ : state) {
		for (int frame = 0; frame < 25; ++frame, ++n) {
			ns += 40'000'000;
			estimator.addColour(colour[n % colour.size()].rgb, ns);
			if (frame % 5 == 2)
				estimator.addDepth(depth[n % depth.size()], ns);
		}
		benchmark::DoNotOptimize(estimator.estimate());
	}
}
BENCHMARK(BM_LatencyEstimatorSecond)->Unit(benchmark::kMicrosecond);

} // namespace
