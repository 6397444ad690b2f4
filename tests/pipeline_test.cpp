// The whole pipeline on the skeleton's simulated scene (hal/sim/simple_scene:
// same scene for both cameras, ground truth from figureAt) and on synthetic
// frames: accuracy against the depth-only keyer, zero heap allocations per
// frame in steady state, seeding once per depth frame. Its stages have
// their own tests (depth_mapper_test, morphology_test, depth_seeder_test).
#include "algo/depth_range_keyer.hpp"
#include "algo/pipeline.hpp"
#include "hal/sim/sim_sequence.hpp"
#include "hal/sim/simple_scene.hpp"
#include "tests/allocation_counter.hpp"
#include "tests/synthetic_still.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

using namespace depthkey;
using namespace depthkey::test;

namespace {

struct SimFrames {
	SimpleScene scene{ 1 };
	ColourFrame colour;
	DepthFrame depth;
	Gray8Image truth;

	SimFrames(int w, int h)
	{
		colour.rgb.resize(w, h);
		depth.depthMm.resize(160, 124);
		depth.amplitude.resize(160, 124);
		depth.intensity.resize(160, 124);
		truth.resize(w, h);
	}
	void render(double t)
	{
		scene.renderColour(t, colour.rgb);
		scene.renderDepth(t, depth);
		for (int y = 0; y < truth.height(); ++y)
			for (int x = 0; x < truth.width(); ++x)
				truth.at(x, y) = scene.figureAt(t, (x + 0.5) / truth.width(), (y + 0.5) / truth.height()) ? 255 : 0;
	}
};

MappingModel identity(int w, int h)
{
	MappingModel m;
	m.colourWidth = w;
	m.colourHeight = h;
	return m;
}

} // namespace

TEST(Pipeline, BeatsTheDepthOnlyKeyerOnTheSimulatedScene)
{
	SimFrames sim(640, 480);
	Pipeline pipeline;
	pipeline.configure(PipelineSettings{}, identity(640, 480));
	DepthRangeKeyer keyer;
	keyer.configure(640, 480, 160, 124);
	PipelineOutput out;
	Gray8Image depthOnly;
	double iouPipeline = 0, iouDepth = 0;
	int scored = 0;
	for (int frame = 0; frame < 60; ++frame) {
		sim.render(frame * 0.04);
		pipeline.process(sim.colour, sim.depth, out);
		if (frame < 25)
			continue; // learning
		keyer.key(sim.depth.depthMm, 500, 1600, depthOnly);
		iouPipeline += intersectionOverUnion(out.alpha, sim.truth);
		iouDepth += intersectionOverUnion(depthOnly, sim.truth);
		++scored;
	}
	EXPECT_FALSE(pipeline.status().learning);
	EXPECT_GT(pipeline.status().lecturerCentroids, 0u);
	std::printf("simple scene, %d frames: mean IoU pipeline %.4f, depth-only %.4f\n", scored,
		    iouPipeline / scored, iouDepth / scored);
	EXPECT_GE(iouPipeline / scored, 0.97);
	EXPECT_GT(iouPipeline / scored, iouDepth / scored);
}

// The band's minimum cut (algo/band_graph_cut.hpp) is the one stage that
// allocates per frame: OpenCV's max-flow graph has no reset, so it is made
// anew, a few blocks sized by the band. Every other stage allocates nothing;
// with the cut, at most this many blocks a frame.
constexpr size_t kCutAllocationsPerFrame = 16;

TEST(Pipeline, NoHeapAllocationPerFrameInSteadyState)
{
	if (!allocationCounting())
		GTEST_SKIP() << "allocations are not counted under AddressSanitizer (the plain build counts them)";
	for (int cut : { 0, Settings{}.decision.cutSmoothness })
	for (auto [w, h] : { std::pair{ 640, 480 }, std::pair{ 960, 540 } }) {
		SimFrames sim(w, h);
		Pipeline pipeline;
		Settings settings;
		settings.learning.initialFrames = 30; // the first derivation falls in the counted frames
		settings.decision.cutSmoothness = cut;
		pipeline.configure(PipelineSettings::from(settings), identity(w, h));
		PipelineOutput out;
		for (int frame = 0; frame < 25; ++frame) { // warm-up: buffers reach their sizes
			sim.render(frame * 0.04);
			pipeline.process(sim.colour, sim.depth, out);
		}
		int derivationsBefore = pipeline.status().derivations;
		size_t allocations = 0;
		for (int frame = 25; frame < 45; ++frame) {
			sim.render(frame * 0.04);
			CountAllocations counter;
			pipeline.process(sim.colour, sim.depth, out);
			allocations += counter.count();
		}
		EXPECT_LE(allocations, cut ? 20 * kCutAllocationsPerFrame : 0u) << w << "x" << h << ", cut " << cut;
		EXPECT_GT(pipeline.status().derivations, derivationsBefore);
		std::printf("%dx%d, cut %d: 20 frames, %d signature derivations, %zu allocations\n", w, h, cut,
			    pipeline.status().derivations - derivationsBefore, allocations);
	}
}

TEST(Pipeline, NoHeapAllocationPerFrameOnTheSimulatedLecture)
{
	// The lecture scene with every artefact: noise scatters the depth image
	// into many more components than the simple scene has, and the
	// lecturer walks, writes, leaves and comes back.
	if (!allocationCounting())
		GTEST_SKIP() << "allocations are not counted under AddressSanitizer (the plain build counts them)";
	for (int cut : { 0, Settings{}.decision.cutSmoothness }) {
		Settings settings;
		settings.decision.cutSmoothness = cut;
		SimSequence sequence;
		sequence.configure(settings.sim, 640, 480, settings.colour.fps, settings.depth.fps);
		Pipeline pipeline;
		pipeline.configure(PipelineSettings::from(settings), identity(640, 480));
		PipelineOutput out;
		GroundTruth truth;
		DepthFrame latest;
		ColourFrame colour;
		size_t allocations = 0;
		for (uint64_t n = 0; n < 300; ++n) {
			sequence.frame(n, colour, truth, [&](const DepthFrame &d) { latest = d; });
			if (latest.depthMm.empty())
				continue;
			CountAllocations counter;
			pipeline.process(colour, latest, out);
			if (n >= 30) // warm-up: buffers reach their sizes
				allocations += counter.count();
		}
		EXPECT_LE(allocations, cut ? 270 * kCutAllocationsPerFrame : 0u) << "cut " << cut;
		std::printf("simulated lecture, cut %d: 270 frames, %zu allocations\n", cut, allocations);
	}
}

TEST(Pipeline, SeedsOncePerDepthFrameAndAgainAfterNewSettings)
{
	SimFrames sim(320, 240);
	Pipeline pipeline;
	Settings settings;
	pipeline.configure(PipelineSettings::from(settings), identity(320, 240));
	PipelineOutput out;
	sim.render(1.0);
	sim.depth.timestampNs = 1'000'000'000;
	sim.depth.sequence = 7;
	pipeline.process(sim.colour, sim.depth, out);
	const Gray8Image first = pipeline.trimap();
	// The next colour frame keyed with the same depth frame: the same
	// seeds, although the depth image buffer now holds something else (a
	// caller may reuse it; the frame's identity is its time and sequence).
	ColourFrame later = sim.colour;
	sim.render(1.04);
	later.rgb = sim.colour.rgb;
	sim.render(2.0);
	DepthFrame same = sim.depth;
	same.timestampNs = 1'000'000'000;
	same.sequence = 7;
	pipeline.process(later, same, out);
	EXPECT_TRUE(std::equal(first.data(), first.data() + first.size(), pipeline.trimap().data()));
	// New settings seed the same frame again.
	settings.segmentation.dilatePx = 8;
	pipeline.configure(PipelineSettings::from(settings), identity(320, 240));
	pipeline.process(later, same, out);
	EXPECT_FALSE(std::equal(first.data(), first.data() + first.size(), pipeline.trimap().data()));
	// A new depth frame (the figure has moved by t = 2 s) is seeded.
	settings.segmentation.dilatePx = Settings{}.segmentation.dilatePx;
	pipeline.configure(PipelineSettings::from(settings), identity(320, 240));
	same.sequence = 8;
	pipeline.process(later, same, out);
	const Gray8Image moved = pipeline.trimap();
	EXPECT_FALSE(std::equal(first.data(), first.data() + first.size(), moved.data()));
	sim.render(1.0);
	sim.depth.timestampNs = 1'100'000'000;
	sim.depth.sequence = 9;
	pipeline.process(later, sim.depth, out); // no new settings: seeded for being new
	EXPECT_FALSE(std::equal(moved.data(), moved.data() + moved.size(), pipeline.trimap().data()));
}

// Without a composite image of its own (setMakeComposite(false): the daemon
// makes it in the recorder's shared memory), the pipeline's composite parts
// give the bytes it would have made, frame after frame, and its alpha is
// untouched by the choice.
TEST(Pipeline, CompositeInputsMakeTheCompositeItWouldHaveMade)
{
	SimFrames sim(320, 240);
	Settings settings;
	settings.learning.initialFrames = 3;
	Pipeline making, notMaking;
	making.configure(PipelineSettings::from(settings), identity(320, 240));
	notMaking.configure(PipelineSettings::from(settings), identity(320, 240));
	notMaking.setMakeComposite(false);
	PipelineOutput made, parts;
	RgbImage fromParts;
	for (int frame = 0; frame < 12; ++frame) {
		sim.render(frame * 0.04);
		making.process(sim.colour, sim.depth, made);
		notMaking.process(sim.colour, sim.depth, parts);
		ASSERT_FALSE(made.composite.empty());
		EXPECT_TRUE(parts.composite.empty()) << frame;
		EXPECT_EQ(parts.alpha, made.alpha) << frame;
		const CompositeInputs in = notMaking.compositeInputs(sim.colour.rgb, parts.alpha);
		fromParts.resize(in.width(), in.height());
		for (int y = 0; y < in.height(); ++y)
			compositeRoiRow(in, y, fromParts.row(y));
		EXPECT_EQ(fromParts, made.composite) << frame;
	}
	// Pass-through (no depth): no image either, the colour frame is the composite.
	notMaking.passThrough(sim.colour, parts);
	EXPECT_TRUE(parts.composite.empty());
}

// Issue 29 point 4: a colour frame keyed with depth from half a second
// before it (no depth within pairing.max_skew_ms) gets a superset grown by
// how far the lecturer can walk in that time, so that it holds where he is
// now, not where depth saw him; in steady state that allocates nothing.
TEST(Pipeline, StaleDepthGrowsTheSupersetToHoldTheMovedLecturer)
{
	constexpr int kW = 640, kH = 480;
	SimFrames sim(kW, kH), old(kW, kH);
	Pipeline pipeline;
	Settings settings;
	settings.decision.cutSmoothness = 0; // the cut allocates per frame (above); the growth must not
	pipeline.configure(PipelineSettings::from(settings), identity(kW, kH));
	PipelineOutput out;
	for (int frame = 0; frame < 40; ++frame) {
		sim.render(frame * 0.04);
		pipeline.process(sim.colour, sim.depth, out);
	}
	// The fraction of the lecturer (truth) inside the superset.
	auto covered = [&](const Gray8Image &truth) {
		size_t in = 0, all = 0;
		for (int y = 0; y < kH; ++y)
			for (int x = 0; x < kW; ++x)
				if (truth.at(x, y)) {
					++all;
					in += pipeline.trimap().at(x, y) != kTrimapBoard;
				}
		return all ? double(in) / double(all) : 0.0;
	};
	constexpr int64_t kGapNs = 500'000'000;
	const double t = 3.0;
	sim.render(t);
	old.render(t - kGapNs * 1e-9);
	sim.colour.timestampNs = uint64_t(t * 1e9);
	old.depth.timestampNs = sim.colour.timestampNs - kGapNs;
	FramePairer::Bracket stale;
	stale.before = &old.depth;
	stale.beforeNs = int64_t(old.depth.timestampNs);
	FramePairer::Bracket unflagged = stale; // the same depth, not known stale
	stale.staleNs = kGapNs;

	pipeline.process(sim.colour, unflagged, out);
	const double plain = covered(sim.truth);
	pipeline.process(sim.colour, stale, out);
	const double grown = covered(sim.truth);
	const int margin = Pipeline::staleMarginPx(kW, kGapNs);
	std::printf("stale depth (500 ms): margin %d px, lecturer in the superset %.4f (ungrown %.4f), IoU %.4f\n",
		    margin, grown, plain, intersectionOverUnion(out.alpha, sim.truth));
	EXPECT_EQ(margin, kW / 4); // 160 px walked in 0.5 s, the cap
	EXPECT_EQ(Pipeline::staleMarginPx(kW, 100'000'000), 32);
	EXPECT_LT(plain, 0.99) << "the simulated lecturer did not move: the test shows nothing";
	EXPECT_GE(grown, 0.999);
	EXPECT_GT(intersectionOverUnion(out.alpha, sim.truth), 0.8);

	if (!allocationCounting())
		return;
	CountAllocations counter;
	pipeline.process(sim.colour, stale, out);
	EXPECT_EQ(counter.count(), 0u);
}
