// Per-frame cost of the pipeline and of each stage (mapping + seeding,
// learning, SIOX on the band with post-processing, compositing), on the
// skeleton's simulated scene after learning, at 640x480 and 1920x1080 colour
// with 160x124 depth; and depthkey-siox's segmentation of a 640x480 still
// with a 10 px band.
#include "algo/colour_learner.hpp"
#include "algo/composite.hpp"
#include "algo/depth_mapper.hpp"
#include "algo/depth_seeder.hpp"
#include "algo/board_picture_prior.hpp"
#include "algo/pipeline.hpp"
#include "algo/seed_mapper.hpp"
#include "algo/siox_refiner.hpp"
#include "algo/still_siox.hpp"
#include "hal/kernel_path_env.hpp"
#include "hal/sim/board_display.hpp"
#include "hal/sim/sim_sequence.hpp"
#include "hal/sim/simple_scene.hpp"
#include "tests/synthetic_still.hpp"

#include <benchmark/benchmark.h>

#include <functional>
#include <map>
#include <memory>
#include <vector>

using namespace depthkey;

namespace {

constexpr int kFrames = 8; // distinct frames cycled through (motion, new colours)

struct Inputs {
	std::vector<ColourFrame> colour;
	std::vector<DepthFrame> depth;
};

const Inputs &inputs(int w, int h)
{
	static std::map<std::pair<int, int>, std::unique_ptr<Inputs>> cache;
	auto &slot = cache[{ w, h }];
	if (!slot) {
		slot = std::make_unique<Inputs>();
		SimpleScene scene(1);
		for (int i = 0; i < kFrames; ++i) {
			ColourFrame c;
			c.rgb.resize(w, h);
			scene.renderColour(1.0 + i * 0.04, c.rgb);
			DepthFrame d;
			d.depthMm.resize(160, 124);
			d.amplitude.resize(160, 124);
			d.intensity.resize(160, 124);
			scene.renderDepth(1.0 + i * 0.04, d);
			slot->colour.push_back(std::move(c));
			slot->depth.push_back(std::move(d));
		}
	}
	return *slot;
}

// Frames of the simulated lecture (every artefact on), from 8 s on, when the
// lecturer stands at the board writing: each colour frame with the depth
// frame that arrived last before it.
const Inputs &lectureInputs(int w, int h)
{
	static std::map<std::pair<int, int>, std::unique_ptr<Inputs>> cache;
	auto &slot = cache[{ w, h }];
	if (!slot) {
		slot = std::make_unique<Inputs>();
		Settings s;
		SimSequence sequence;
		sequence.configure(s.sim, w, h, s.colour.fps, s.depth.fps);
		GroundTruth truth;
		DepthFrame latest;
		for (uint64_t n = 0; n < 200 + kFrames; ++n) {
			ColourFrame c;
			sequence.frame(n, c, truth, [&](const DepthFrame &d) { latest = d; });
			if (n >= 200 && !latest.depthMm.empty()) {
				slot->colour.push_back(std::move(c));
				slot->depth.push_back(latest);
			}
		}
	}
	return *slot;
}

MappingModel identity(int w, int h)
{
	MappingModel m;
	m.colourWidth = w;
	m.colourHeight = h;
	return m;
}

void pipelineFrame(benchmark::State &state, const Inputs &in, void (*adjust)(PipelineSettings &) = nullptr,
		   const std::function<void(Pipeline &)> &prepare = {})
{
	const int w = int(state.range(0)), h = int(state.range(1));
	auto pipeline = std::make_unique<Pipeline>();
	PipelineSettings settings;
	if (adjust)
		adjust(settings);
	pipeline->configure(settings, identity(w, h));
	pipeline->setKernelPath(kernelPathFromEnvironment());
	if (prepare)
		prepare(*pipeline);
	PipelineOutput out;
	for (int i = 0; i < 30; ++i) // past learning
		pipeline->process(in.colour[i % kFrames], in.depth[i % kFrames], out);
	int i = 0;
	for (auto _ : state) {
		pipeline->process(in.colour[i % kFrames], in.depth[i % kFrames], out);
		++i;
		benchmark::DoNotOptimize(out.alpha.data());
	}
	state.counters["band_px"] = double(pipeline->status().bandPixels);
}

// The skeleton's simple scene (a figure in front of a plain board).
void BM_PipelineFrame(benchmark::State &state)
{
	pipelineFrame(state, inputs(int(state.range(0)), int(state.range(1))));
}

// The simulated lecture: a larger lecturer, a desk, board writing, noise.
void BM_PipelineFrameLecture(benchmark::State &state)
{
	pipelineFrame(state, lectureInputs(int(state.range(0)), int(state.range(1))));
}

// The same with the board's own picture teaching the board model
// (algo/board_picture_prior.hpp), the simulated board's 1920x780 picture
// mapped over the whole colour image: every pixel on the display, the most
// the prior can cost (in the simulated room it covers about 80%).
void BM_PipelineFrameLectureBoardPicture(benchmark::State &state)
{
	const int w = int(state.range(0)), h = int(state.range(1));
	static RgbImage picture;
	SimBoardDisplay display;
	display.configure(Settings().sim, 1920);
	display.render(9.0, picture);
	pipelineFrame(state, lectureInputs(w, h), nullptr, [&](Pipeline &p) {
		p.setBoardGeometry(boardScaling(w, h, picture.width(), picture.height()), RadialLens::forImage(w, h, 0, 0), picture.width(),
				   picture.height());
		p.setBoardPicture(&picture);
	});
}

// The board picture prior alone, per frame: the gain fitted and the
// prediction made (predict), then taught to the board model (teach), with
// every colour pixel on the display. What BM_PipelineFrameLectureBoardPicture
// adds to BM_PipelineFrameLecture, measured without the whole frame's noise.
void BM_BoardPicturePrior(benchmark::State &state)
{
	const int w = int(state.range(0)), h = int(state.range(1));
	const Inputs &in = lectureInputs(w, h);
	RgbImage picture;
	SimBoardDisplay display;
	display.configure(Settings().sim, 1920);
	display.render(9.0, picture);
	BoardPicturePrior prior;
	prior.configure(w, h, boardScaling(w, h, picture.width(), picture.height()), RadialLens::forImage(w, h, 0, 0), picture.width(),
			picture.height());
	BoardModel model;
	const Gray8Image allBoard(w, h, kTrimapBoard);
	for (int k = 0; k < 16; ++k) // learn() visits a phase of the rows per call
		model.learn(in.colour[0].rgb, allBoard);
	int i = 0, taught = 0;
	for (auto _ : state) {
		const RgbImage &colour = in.colour[i++ % kFrames].rgb;
		if (prior.predict(picture, colour, model)) {
			model.teach(prior.sampled(), prior.gainQ8(), prior.onDisplay());
			taught++;
		}
		benchmark::DoNotOptimize(model.row(0));
	}
	state.counters["taught"] = double(taught) / std::max(1, i); // 1: every frame predicted and taught
}

// The same without the band's minimum cut: what the cut costs.
void BM_PipelineFrameLectureNoCut(benchmark::State &state)
{
	// The band smoothed instead (algo/siox_refiner.hpp).
	pipelineFrame(state, lectureInputs(int(state.range(0)), int(state.range(1))),
		      [](PipelineSettings &s) { s.decision.cutSmoothness = 0; });
}

// The cut solved whole at full resolution (no coarse levels), as before
// issue 28: what the coarse-to-fine solve saves.
void BM_PipelineFrameLectureWholeCut(benchmark::State &state)
{
	pipelineFrame(state, lectureInputs(int(state.range(0)), int(state.range(1))), [](PipelineSettings &s) {
		s.decision.cutLevels = 0;
		s.decision.cutMaxBandPixels = 8294400;
	});
}

// The same without the edge unmixing: what it costs.
void BM_PipelineFrameLectureNoUnmixing(benchmark::State &state)
{
	pipelineFrame(state, lectureInputs(int(state.range(0)), int(state.range(1))),
		      [](PipelineSettings &s) { s.decision.edgeUnmixing = 0; });
}

// The stages one by one, with the state a running pipeline has.
struct Stages {
	QuantisedLab lab;
	SioxClassifier classifier{ lab };
	ColourLearner learner{ lab };
	DepthMapper mapper;
	DepthSeeder seeder;
	SeedMapper seedMapper;
	SioxRefiner refiner;
	DepthSeeds seeds;
	MappedSeeds mapped;
	Gray8Image &trimap = mapped.trimap;
	Roi &roi = mapped.roi;
	Gray8Image alpha;
	RgbImage board, composite;
	RgbaImage layer;

	Stages(int w, int h)
	{
		Settings s;
		mapper.configure(identity(w, h));
		seedMapper.configure(mapper);
		seeder.configure(s.segmentation);
		learner.configure(s.learning);
		refiner.configure(s.siox);
		board = RgbImage(w, h, Rgb8{ 30, 60, 40 });
		const Inputs &in = inputs(w, h);
		for (int i = 0; i < 30; ++i)
			run(in, i);
	}
	void seed(const Inputs &in, int i)
	{
		seeder.seed(in.depth[i % kFrames], seeds);
		seedMapper.map(seeds, mapped);
	}
	void run(const Inputs &in, int i)
	{
		seed(in, i);
		learner.learn(in.colour[i % kFrames].rgb, trimap, 8, classifier);
		refiner.refine(in.colour[i % kFrames].rgb, trimap, roi, classifier, alpha);
	}
};

void BM_Stage(benchmark::State &state, int stage)
{
	const int w = int(state.range(0)), h = int(state.range(1));
	const Inputs &in = inputs(w, h);
	auto s = std::make_unique<Stages>(w, h);
	int i = 0;
	for (auto _ : state) {
		const RgbImage &rgb = in.colour[i % kFrames].rgb;
		switch (stage) {
		case 0:
			s->seed(in, i);
			break;
		case 1:
			s->learner.learn(rgb, s->trimap, 8, s->classifier);
			break;
		case 2:
			s->refiner.refine(rgb, s->trimap, s->roi, s->classifier, s->alpha);
			break;
		default:
			compositeRoi(rgb, s->alpha, s->board, s->roi, 128, s->composite, kernelPathFromEnvironment());
			lecturerLayer(rgb, s->alpha, s->layer, kernelPathFromEnvironment());
			break;
		}
		++i;
		benchmark::ClobberMemory();
	}
}

void BM_SeedAndMap(benchmark::State &state) { BM_Stage(state, 0); }
void BM_Learn(benchmark::State &state) { BM_Stage(state, 1); }
void BM_SioxBand(benchmark::State &state) { BM_Stage(state, 2); }
void BM_CompositeOutputs(benchmark::State &state) { BM_Stage(state, 3); }

void BM_DepthkeySioxStill(benchmark::State &state)
{
	test::SyntheticStill still = test::makeStill(640, 480, 10, 2);
	auto siox = std::make_unique<StillSiox>();
	Gray8Image mask, alpha;
	for (auto _ : state) {
		siox->segment(still.image, still.trimap, mask, alpha);
		benchmark::DoNotOptimize(mask.data());
	}
}

// What one depthkey-siox run does between reading and writing its files: a
// fresh StillSiox (its colour table filled on demand) and one segmentation.
void BM_DepthkeySioxStillCold(benchmark::State &state)
{
	test::SyntheticStill still = test::makeStill(640, 480, 10, 2);
	Gray8Image mask, alpha;
	for (auto _ : state) {
		auto siox = std::make_unique<StillSiox>();
		siox->segment(still.image, still.trimap, mask, alpha);
		benchmark::DoNotOptimize(mask.data());
	}
}

} // namespace

#define SIZES ->Args({ 640, 480 })->Args({ 1920, 1080 })->Unit(benchmark::kMicrosecond)
BENCHMARK(BM_PipelineFrame) SIZES;
BENCHMARK(BM_PipelineFrameLecture) SIZES;
BENCHMARK(BM_PipelineFrameLectureBoardPicture) SIZES;
BENCHMARK(BM_BoardPicturePrior) SIZES;
BENCHMARK(BM_PipelineFrameLectureNoCut) SIZES;
BENCHMARK(BM_PipelineFrameLectureWholeCut) SIZES;
BENCHMARK(BM_PipelineFrameLectureNoUnmixing) SIZES;
BENCHMARK(BM_SeedAndMap) SIZES;
BENCHMARK(BM_Learn) SIZES;
BENCHMARK(BM_SioxBand) SIZES;
BENCHMARK(BM_CompositeOutputs) SIZES;
BENCHMARK(BM_DepthkeySioxStill)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_DepthkeySioxStillCold)->Unit(benchmark::kMicrosecond);
