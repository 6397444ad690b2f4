// The whole pipeline on the skeleton's simulated scene (hal/sim/simple_scene:
// same scene for both cameras, ground truth from figureAt) and on synthetic
// frames: accuracy against the depth-only keyer, zero heap allocations per
// frame in steady state, the fixed-point mapping against MappingModel, and
// the seeding stages against simple references.
#include "algo/depth_mapper.hpp"
#include "algo/depth_range_keyer.hpp"
#include "algo/depth_seeder.hpp"
#include "algo/mask_rows.hpp"
#include "algo/morphology.hpp"
#include "algo/pipeline.hpp"
#include "hal/sim/sim_sequence.hpp"
#include "hal/sim/simple_scene.hpp"
#include "tests/allocation_counter.hpp"
#include "tests/synthetic_still.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

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
	pipeline.configure(Settings{}, identity(640, 480));
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

TEST(Pipeline, NoHeapAllocationPerFrameInSteadyState)
{
	if (!allocationCounting())
		GTEST_SKIP() << "allocations are not counted under AddressSanitizer (the plain build counts them)";
	for (auto [w, h] : { std::pair{ 640, 480 }, std::pair{ 960, 540 } }) {
		SimFrames sim(w, h);
		Pipeline pipeline;
		Settings settings;
		settings.learning.initialFrames = 30; // the first derivation falls in the counted frames
		pipeline.configure(settings, identity(w, h));
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
		EXPECT_EQ(allocations, 0u) << w << "x" << h;
		EXPECT_GT(pipeline.status().derivations, derivationsBefore);
		std::printf("%dx%d: 20 frames, %d signature derivations, %zu allocations\n", w, h,
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
	Settings settings;
	SimSequence sequence;
	sequence.configure(settings.sim, 640, 480, settings.colour.fps, settings.depth.fps);
	Pipeline pipeline;
	pipeline.configure(settings, identity(640, 480));
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
	EXPECT_EQ(allocations, 0u);
	std::printf("simulated lecture: 270 frames, %zu allocations\n", allocations);
}

TEST(DepthMapper, FixedPointWithinHalfAPixelOfTheModel)
{
	// A paper model and a parallax model with coefficients of the size a
	// calibration gives (tens of pixels of parallax at 1 m).
	for (MappingKind kind : { MappingKind::Paper, MappingKind::Parallax }) {
		MappingModel model;
		model.kind = kind;
		model.colourWidth = 1920;
		model.colourHeight = 1080;
		if (kind == MappingKind::Paper) {
			model.x = { 960, 1000, 5, -30, 12 };
			model.y = { 540, 560, -4, 20, -8 };
		} else {
			model.x = { 940, 1010, 8, 3, -6, 2, -35, 4, -3, 1, 40, -3, 2, 6 };
			model.y = { 530, 5, 570, -2, 4, 3, 2, -28, 3, 1, -6, 1, -2, -3 };
		}
		DepthMapper mapper;
		mapper.configure(model);
		double worst = 0;
		for (int v = 0; v < model.tofHeight; v += 3)
			for (int u = 0; u < model.tofWidth; u += 3)
				for (int z = 400; z <= 7500; z += 137) {
					double x, y;
					model.map(u, v, z / 1000.0, x, y);
					int32_t xq, yq;
					mapper.map(v * model.tofWidth + u, z, xq, yq);
					worst = std::max({ worst, std::fabs(xq / 256.0 - x), std::fabs(yq / 256.0 - y) });
				}
		std::printf("mapping %s: max |fixed - model| = %.5f px\n", mappingKindName(kind), worst);
		EXPECT_LE(worst, 0.5);
		EXPECT_LE(worst, 0.01); // in fact: Q8 rounding
	}
}

TEST(Morphology, ErodeAndDilateMatchBruteForce)
{
	std::mt19937 rng(2);
	std::bernoulli_distribution on(0.6);
	Gray8Image in(37, 23), out;
	MorphologyScratch scratch;
	for (int trial = 0; trial < 4; ++trial) {
		for (size_t i = 0; i < in.size(); ++i)
			in.data()[i] = on(rng) ? 255 : 0;
		for (int r = 0; r <= 5; ++r)
			for (bool erode : { true, false }) {
				KernelPath path = trial % 2 ? KernelPath::C : KernelPath::Sse2;
				(erode ? erodeSquare : dilateSquare)(in, r, out, scratch, path);
				for (int y = 0; y < in.height(); ++y)
					for (int x = 0; x < in.width(); ++x) {
						bool all = true, any = false;
						for (int yy = std::max(0, y - r); yy <= std::min(in.height() - 1, y + r); ++yy)
							for (int xx = std::max(0, x - r); xx <= std::min(in.width() - 1, x + r); ++xx) {
								all = all && in.at(xx, yy);
								any = any || in.at(xx, yy);
							}
						ASSERT_EQ(out.at(x, y), (erode ? all : any) ? 255 : 0) << r << " " << x << "," << y;
					}
			}
	}
}

// The SSE2 mask rows against the C rows, bit for bit, for odd widths and
// unaligned pointers.
TEST(Morphology, Sse2MaskRowsEqualTheCRows)
{
	std::mt19937 rng(4);
	std::uniform_int_distribution<int> byte(0, 255);
	for (int width : { 0, 1, 15, 16, 17, 33, 160, 161 }) {
		for (int offset : { 0, 1, 3 }) {
			std::vector<uint8_t> acc(width + offset), src(width + offset);
			for (int i = 0; i < width + offset; ++i) {
				acc[i] = uint8_t(byte(rng));
				src[i] = uint8_t(byte(rng));
			}
			for (bool erode : { false, true }) {
				std::vector<uint8_t> c = acc, sse = acc;
				maskRow(KernelPath::C, erode)(c.data() + offset, src.data() + offset, width);
				maskRow(KernelPath::Sse2, erode)(sse.data() + offset, src.data() + offset, width);
				ASSERT_EQ(c, sse) << "width " << width << " offset " << offset << " erode " << erode;
			}
		}
	}
}

TEST(Morphology, ComponentLabelsMatchAFloodFillReference)
{
	std::mt19937 rng(8);
	std::bernoulli_distribution on(0.5);
	ComponentScratch scratch;
	for (int trial = 0; trial < 20; ++trial) {
		Gray8Image mask(31, 17);
		for (size_t i = 0; i < mask.size(); ++i)
			mask.data()[i] = on(rng) ? 255 : 0;
		// Reference: label by repeated relaxation (min label of 4-neighbours).
		const int w = mask.width(), n = int(mask.size());
		std::vector<int> label(n);
		for (int i = 0; i < n; ++i)
			label[i] = mask.data()[i] ? i : -1;
		for (bool changed = true; changed;) {
			changed = false;
			for (int i = 0; i < n; ++i) {
				if (label[i] < 0)
					continue;
				int x = i % w;
				for (int q : { x > 0 ? i - 1 : -1, x + 1 < w ? i + 1 : -1, i - w, i + w < n ? i + w : -1 })
					if (q >= 0 && label[q] >= 0 && label[q] < label[i]) {
						label[i] = label[q];
						changed = true;
					}
			}
		}
		std::vector<int> size(n, 0);
		for (int l : label)
			if (l >= 0)
				size[l]++;
		int best = -1;
		for (int i = 0; i < n; ++i)
			if (best < 0 || size[i] > size[best])
				best = i;
		// The largest labelled component (the first in raster order on a
		// tie) is the reference's largest, pixel for pixel.
		Gray8Image got = mask;
		const int count = labelComponents(got, scratch);
		int largest = -1;
		for (int k = 0; k < count; ++k)
			if (largest < 0 || scratch.sizes[size_t(k)] > scratch.sizes[size_t(largest)])
				largest = k;
		keepComponent(got, scratch, largest);
		const int kept = largest >= 0 ? scratch.sizes[size_t(largest)] : 0;
		ASSERT_EQ(kept, size[best]);
		for (int i = 0; i < n; ++i)
			ASSERT_EQ(got.data()[i] != 0, label[i] == best) << trial << " " << i;
	}
}

namespace {

// A 40 x 30 depth frame: the board at 2000 mm, a lecturer in [10, 30) x
// [5, 25) at depthAt(x, y), amplitude 3000 everywhere.
template<typename DepthAt>
DepthFrame boardWithLecturer(DepthAt depthAt)
{
	DepthFrame depth;
	depth.depthMm = Gray16Image(40, 30, 2000);
	depth.amplitude = Gray16Image(40, 30, 3000);
	for (int y = 5; y < 25; ++y)
		for (int x = 10; x < 30; ++x)
			depth.depthMm.at(x, y) = depthAt(x, y);
	return depth;
}

// The seeds of a frame with erode 1, dilate 2 and the given amplitude limit.
DepthSeeds seedsOf(const DepthFrame &depth, int maxAmplitude = SegmentationSettings{}.maxAmplitude)
{
	SegmentationSettings settings;
	settings.maxAmplitude = maxAmplitude;
	settings.erodePx = 1;
	settings.dilatePx = 2;
	DepthSeeder seeder;
	seeder.configure(settings);
	DepthSeeds seeds;
	seeder.seed(depth, seeds);
	return seeds;
}

} // namespace

TEST(DepthSeeder, RejectsUntrustedDepthAndSeparatesSubsetBandAndBoard)
{
	DepthFrame depth = boardWithLecturer([](int, int) { return uint16_t(1200); });
	for (int y = 0; y < 3; ++y)
		for (int x = 0; x < 3; ++x)
			depth.depthMm.at(x, y) = 1000; // small in-range blob: not the largest
	depth.amplitude.at(20, 15) = 65535;       // saturated inside the lecturer
	const DepthSeeds seeds = seedsOf(depth, 60000);
	EXPECT_EQ(seeds.labels.at(15, 10), kTrimapLecturer);
	EXPECT_EQ(seeds.labels.at(20, 15), kTrimapUndecided); // untrusted: eroded around
	EXPECT_EQ(seeds.labels.at(10, 5), kTrimapInRange);    // the edge: in range, eroded away
	EXPECT_EQ(seeds.labels.at(12, 7), kTrimapSubset);     // eroded once, not deep enough for the core
	EXPECT_EQ(seeds.labels.at(9, 15), kTrimapUndecided);  // dilated beyond
	EXPECT_EQ(seeds.labels.at(8, 15), kTrimapUndecided);  // the in-range area, dilated
	EXPECT_EQ(seeds.labels.at(7, 15), kTrimapBoard);
	EXPECT_EQ(seeds.labels.at(1, 1), kTrimapBoard);       // smaller blob
	EXPECT_EQ(seeds.labels.at(37, 15), kTrimapBoard);
	EXPECT_EQ(seeds.lecturerDepthMm, 1200);
}

TEST(DepthSeeder, SurfaceDepthIsTheLecturersSmoothedDepth)
{
	// A lecturer whose depth alternates 1300 / 1700 mm (noise) in front of
	// the board at 2000 mm.
	const DepthSeeds seeds =
		seedsOf(boardWithLecturer([](int x, int y) { return uint16_t((x + y) % 2 ? 1300 : 1700); }));
	ASSERT_EQ(seeds.labels.at(20, 15), kTrimapLecturer);
	EXPECT_NEAR(seeds.surfaceMm.at(20, 15), 1500, 10); // 7 x 7 mean (radius dilate + 1)
	EXPECT_NEAR(seeds.surfaceMm.at(11, 6), 1500, 25);  // near the corner: fewer
	ASSERT_EQ(seeds.labels.at(8, 15), kTrimapUndecided);
	EXPECT_NEAR(seeds.surfaceMm.at(8, 15), 1500, 25);  // band on the board: his depth
	EXPECT_EQ(seeds.labels.at(2, 2), kTrimapBoard);
	EXPECT_EQ(seeds.surfaceMm.at(2, 2), 0);
}

TEST(Pipeline, SeedsOncePerDepthFrameAndAgainAfterNewSettings)
{
	SimFrames sim(320, 240);
	Pipeline pipeline;
	Settings settings;
	pipeline.configure(settings, identity(320, 240));
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
	pipeline.configure(settings, identity(320, 240));
	pipeline.process(later, same, out);
	EXPECT_FALSE(std::equal(first.data(), first.data() + first.size(), pipeline.trimap().data()));
	// A new depth frame (the figure has moved by t = 2 s) is seeded.
	settings.segmentation.dilatePx = Settings{}.segmentation.dilatePx;
	pipeline.configure(settings, identity(320, 240));
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
