// The depth seeds (algo/depth_seeder.hpp) of a synthetic board with a
// lecturer in front: untrusted depth rejected, core, band and board told
// apart, and the lecturer's smoothed surface depth.
#include "algo/depth_seeder.hpp"
#include "algo/trimap.hpp"

#include <gtest/gtest.h>

#include <cstdio>

using namespace depthkey;

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
	settings.surfacePx = 3;
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
	EXPECT_NEAR(seeds.surfaceMm.at(20, 15), 1500, 10); // 7 x 7 mean (radius surface_px 3)
	EXPECT_NEAR(seeds.surfaceMm.at(11, 6), 1500, 25);  // near the corner: fewer
	ASSERT_EQ(seeds.labels.at(8, 15), kTrimapUndecided);
	EXPECT_NEAR(seeds.surfaceMm.at(8, 15), 1500, 25);  // band on the board: his depth
	EXPECT_EQ(seeds.labels.at(2, 2), kTrimapBoard);
	EXPECT_EQ(seeds.surfaceMm.at(2, 2), 0);
}

TEST(DepthSeeder, SurfaceRadiusIsItsOwnKeyApartFromTheBand)
{
	// A lecturer leaning towards the camera to his right (1000 + 20 x mm):
	// the band pixel 2 left of him is mapped at the mean depth of his pixels
	// within surface_px, whatever dilate_px makes of the band.
	const DepthFrame depth = boardWithLecturer([](int x, int) { return uint16_t(1000 + 20 * x); });
	auto seedsWith = [&](int dilatePx, int surfacePx) {
		SegmentationSettings settings;
		settings.erodePx = 1;
		settings.dilatePx = dilatePx;
		settings.surfacePx = surfacePx;
		DepthSeeder seeder;
		seeder.configure(settings);
		DepthSeeds seeds;
		seeder.seed(depth, seeds);
		return seeds;
	};
	const DepthSeeds near = seedsWith(2, 3), far = seedsWith(2, 8), wide = seedsWith(5, 8);
	EXPECT_EQ(near.labels, far.labels); // the radius moves no label
	ASSERT_EQ(near.labels.at(8, 15), kTrimapUndecided);
	EXPECT_NEAR(near.surfaceMm.at(8, 15), 1210, 1); // his columns 10..11
	EXPECT_NEAR(far.surfaceMm.at(8, 15), 1260, 1);  // his columns 10..16
	// A wider band with the same radius maps the pixel at the same depth.
	ASSERT_EQ(wide.labels.at(8, 15), kTrimapUndecided);
	EXPECT_EQ(wide.surfaceMm.at(8, 15), far.surfaceMm.at(8, 15));
}

TEST(DepthSeeder, CoreLeavesAHaloFilledGapToTheEvidence)
{
	// A 2 x 2 gap inside the lecturer (between an arm and his side) that
	// the scattered-light halo fills with a depth between his (1200 mm) and
	// the board's (2000 mm): in range and enclosed, so erosion keeps it, but
	// its own depth does not say lecturer, and colour must be able to decide it.
	const DepthSeeds seeds = seedsOf(boardWithLecturer([](int x, int y) {
		return uint16_t(x >= 19 && x < 21 && y >= 14 && y < 16 ? 1600 : 1200);
	}));
	EXPECT_EQ(seeds.labels.at(19, 14), kTrimapSubset);
	EXPECT_EQ(seeds.labels.at(20, 15), kTrimapSubset);
	EXPECT_LT(seeds.evidence.at(20, 15), DepthSeeder::kCoreMinEvidence);
	// Around it his own depth: still the core.
	EXPECT_EQ(seeds.labels.at(17, 15), kTrimapLecturer);
	EXPECT_EQ(seeds.labels.at(20, 12), kTrimapLecturer);
	EXPECT_GE(seeds.evidence.at(17, 15), DepthSeeder::kCoreMinEvidence);
}

TEST(DepthSeeder, HaloFilledGapReadsAsBoardWithTheHaloModel)
{
	// The gap of the test above, its depth the halo's half-way mix, with
	// the board learned behind him (a few frames of the empty room first):
	// against the board's own depth the gap looks like him; against the
	// board as the halo lets it read there (halo_px 4, share 0.5), it is
	// the board.
	auto evidenceInGap = [](int haloPx) {
		SegmentationSettings settings;
		settings.erodePx = 1;
		settings.dilatePx = 2;
		settings.surfacePx = 3;
		settings.haloPx = haloPx;
		DepthSeeder seeder;
		seeder.configure(settings);
		DepthSeeds seeds;
		const DepthFrame empty = boardWithLecturer([](int, int) { return uint16_t(2000); });
		for (int i = 0; i < 20; ++i)
			seeder.seed(empty, seeds);
		seeder.seed(boardWithLecturer([](int x, int y) {
				    return uint16_t(x >= 19 && x < 21 && y >= 14 && y < 16 ? 1600 : 1200);
			    }),
			    seeds);
		return int(seeds.evidence.at(20, 15));
	};
	const int without = evidenceInGap(0), with = evidenceInGap(4);
	std::printf("gap's depth evidence: %d without the halo model, %d with\n", without, with);
	EXPECT_LT(with, without);
	EXPECT_LT(with, 128);
}
