// SeedMapper: the ToF seeds painted into the colour image leave no gaps, even
// where one ToF pixel covers more colour pixels than colour size / ToF size
// (a ToF lens wider than the colour camera's, as in the simulated rig).

#include "algo/depth_mapper.hpp"
#include "algo/seed_mapper.hpp"
#include "tests/simd_paths.hpp"

#include <gtest/gtest.h>

#include <random>

using namespace depthkey;

namespace {

// A solid block of surely-lecturer ToF pixels [u0, u1) x [v0, v1) at zMm.
void solidSeeds(int tw, int th, int u0, int v0, int u1, int v1, int zMm, DepthSeeds &seeds)
{
	seeds.labels.resize(tw, th);
	seeds.surfaceMm.resize(tw, th);
	seeds.lecturerPixels = 0;
	for (int v = 0; v < th; ++v)
		for (int u = 0; u < tw; ++u) {
			bool in = u >= u0 && u < u1 && v >= v0 && v < v1;
			seeds.labels.at(u, v) = in ? kTrimapLecturer : kTrimapBoard;
			seeds.surfaceMm.at(u, v) = uint16_t(in ? zMm : 0);
			seeds.lecturerPixels += in;
		}
	seeds.lecturerDepthMm = zMm;
}

// x2 = 320 + 560 s, y2 = 240 + 420 t: the ToF image spans 1.75 times the
// colour image, so a ToF pixel covers 7 x 6.8 colour pixels, not 4 x 3.9.
MappingModel wideToFLens()
{
	MappingModel model;
	model.kind = MappingKind::Paper;
	model.x = { 319.5, 560, 0, 0, 0 };
	model.y = { 239.5, 420, 0, 0, 0 };
	return model;
}

} // namespace

TEST(SeedMapper, WideToFLensLeavesNoGapsInsideTheMappedSeeds)
{
	const MappingModel model = wideToFLens();
	DepthMapper mapper;
	mapper.configure(model);
	SeedMapper seedMapper;
	seedMapper.configure(mapper);

	DepthSeeds seeds;
	solidSeeds(model.tofWidth, model.tofHeight, 60, 50, 100, 80, 1500, seeds);
	MappedSeeds mapped;
	seedMapper.map(seeds, mapped);
	const Gray8Image &trimap = mapped.trimap;
	const Roi &roi = mapped.roi;

	// The mapped centres of the block's corner pixels bound what must be solid.
	int32_t x0, y0, x1, y1;
	mapper.map(50 * model.tofWidth + 60, 1500, x0, y0);
	mapper.map(79 * model.tofWidth + 99, 1500, x1, y1);
	int holes = 0, inside = 0;
	for (int y = (y0 >> 8) + 1; y < (y1 >> 8); ++y)
		for (int x = (x0 >> 8) + 1; x < (x1 >> 8); ++x) {
			holes += trimap.at(x, y) != kTrimapLecturer;
			++inside;
		}
	EXPECT_GT(inside, 200 * 150);
	EXPECT_EQ(holes, 0);
	// Nothing far outside the block: the footprint is the local step, not more.
	EXPECT_EQ(trimap.at((x0 >> 8) - 10, (y0 >> 8) - 10), kTrimapBoard);
	EXPECT_EQ(trimap.at((x1 >> 8) + 10, (y1 >> 8) + 10), kTrimapBoard);
	EXPECT_FALSE(roi.empty());
}

TEST(SeedMapper, EveryKernelPathPaintsTheCPathsSeeds)
{
	// Random labels, surfaces and evidence on the simulated rig's wide ToF
	// lens: overlapping blocks of every label, blocks cut by the image
	// border (the vector rows' room runs out there): the SIMD paths' trimap,
	// evidence and ROI are the C path's, bit for bit.
	const MappingModel model = wideToFLens();
	DepthMapper mapper;
	mapper.configure(model);
	const int tw = model.tofWidth, th = model.tofHeight;
	DepthSeeds seeds;
	seeds.labels.resize(tw, th);
	seeds.surfaceMm.resize(tw, th);
	seeds.evidence.resize(tw, th);
	std::mt19937 rng(28);
	const uint8_t labels[] = { kTrimapBoard, kTrimapUndecided, kTrimapInRange, kTrimapSubset, kTrimapLecturer };
	for (int i = 0; i < tw * th; ++i) {
		seeds.labels.data()[i] = labels[rng() % 5];
		seeds.surfaceMm.data()[i] = uint16_t(rng() % 8 ? 600 + rng() % 3000 : 0);
		seeds.evidence.data()[i] = uint8_t(rng());
	}
	seeds.lecturerPixels = 1;
	seeds.lecturerDepthMm = 1500;
	SeedMapper reference;
	reference.configure(mapper);
	reference.setKernelPath(KernelPath::C);
	MappedSeeds want;
	reference.map(seeds, want);
	ASSERT_FALSE(want.roi.empty());
	for (KernelPath path : simd_test::kSimdPaths) {
		SeedMapper seedMapper;
		seedMapper.configure(mapper);
		seedMapper.setKernelPath(path);
		MappedSeeds got;
		seedMapper.map(seeds, got);
		EXPECT_EQ(got.trimap, want.trimap) << simd_test::pathName(path);
		EXPECT_EQ(got.evidence, want.evidence) << simd_test::pathName(path);
		EXPECT_EQ(got.roi.x0, want.roi.x0);
		EXPECT_EQ(got.roi.y0, want.roi.y0);
		EXPECT_EQ(got.roi.x1, want.roi.x1);
		EXPECT_EQ(got.roi.y1, want.roi.y1);
		EXPECT_EQ(got.lecturerBeyondBorder, want.lecturerBeyondBorder);
	}
}
