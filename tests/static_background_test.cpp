// StaticBackground and the depth seeder's use of it: a desk standing in the
// lecturer's depth interval (larger than him) is furniture; the lecturer who
// steps in front of the board is the lecturer.

#include "algo/depth_seeder.hpp"
#include "algo/lecturer_picker.hpp"
#include "algo/morphology.hpp"
#include "algo/static_background.hpp"
#include "algo/trimap.hpp"
#include "tests/static_background_per_pixel_box.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace depthkey;

namespace {

// A 60 x 40 room: the board at 2000 mm, a desk (30 x 20 pixels) at 1200 mm
// whose right half is a glossy monitor with +-120 mm of depth noise, and
// optionally a lecturer (10 x 16 pixels) at 1400 mm in front of the board.
void room(bool lecturer, std::mt19937 &random, DepthFrame &frame)
{
	frame.depthMm = Gray16Image(60, 40, 2000);
	frame.amplitude = Gray16Image(60, 40, 3000);
	std::uniform_int_distribution<int> noise(-120, 120);
	for (int y = 15; y < 35; ++y)
		for (int x = 28; x < 58; ++x)
			frame.depthMm.at(x, y) = uint16_t(1200 + (x >= 43 ? noise(random) : 0));
	if (lecturer)
		for (int y = 10; y < 26; ++y)
			for (int x = 5; x < 15; ++x)
				frame.depthMm.at(x, y) = 1400;
}

// A seeder (erode 1, dilate 2, far 1800 mm) that has seen the empty room
// for a second.
void seedEmptyRoom(std::mt19937 &random, DepthSeeder &seeder, DepthSeeds &seeds, DepthFrame &frame)
{
	Settings settings;
	settings.segmentation.erodePx = 1;
	settings.segmentation.dilatePx = 2;
	settings.segmentation.surfacePx = 3;
	settings.segmentation.farMm = 1800;
	seeder.configure(settings.segmentation);
	for (int i = 0; i < 30; ++i) {
		room(false, random, frame);
		seeder.seed(frame, seeds);
	}
}

} // namespace

TEST(StaticBackground, FurnitureAndNoiseAreStaticSomeoneInFrontOfTheBoardMoves)
{
	std::mt19937 random(7);
	StaticBackground background;
	Gray8Image moving;
	DepthFrame frame;
	int noisyMoving = 0;
	for (int i = 0; i < 60; ++i) {
		room(false, random, frame);
		background.update(frame.depthMm, moving);
		for (int y = 15; y < 35; ++y)
			for (int x = 43; x < 58; ++x)
				noisyMoving += moving.at(x, y) != 0;
	}
	EXPECT_EQ(noisyMoving, 0); // the monitor's noise is within twice its deviation
	room(true, random, frame);
	background.update(frame.depthMm, moving);
	EXPECT_EQ(moving.at(10, 18), 255); // 600 mm in front of the board
	EXPECT_EQ(moving.at(30, 20), 0);   // the desk
	EXPECT_EQ(moving.at(2, 2), 0);     // the board
	frame.depthMm.at(2, 2) = 0;        // no measurement: never moving
	background.update(frame.depthMm, moving);
	EXPECT_EQ(moving.at(2, 2), 0);
}

// The ToF's image edge is noisy (about 150 mm there in the simulated
// lecture, up to 30 cm in its corners): an arm reaching in 300 mm in front of
// the board is under one pixel's threshold (150 mm plus twice its deviation),
// and seed 2's arm went unseen for four frames (IoU 0). The mean of a 3x3
// box, with a third of the noise, sees it; the board's noise alone stays
// static.
TEST(StaticBackground, AnArmReachingInAtTheNoisyEdgeMoves)
{
	std::mt19937 random(11);
	std::normal_distribution<double> noise(0.0, 150.0);
	StaticBackground background;
	Gray8Image moving;
	Gray16Image depth(40, 30);
	auto noisy = [&](int x, int y, double mm) { depth.at(x, y) = uint16_t(std::lround(mm + noise(random))); };
	int falseMoving = 0, samples = 0;
	for (int i = 0; i < 260; ++i) {
		for (int y = 0; y < 30; ++y)
			for (int x = 0; x < 40; ++x)
				noisy(x, y, 2000);
		background.update(depth, moving);
		if (i < 60)
			continue; // learning the board's depth and noise
		for (size_t p = 0; p < moving.size(); ++p)
			falseMoving += moving.data()[p] != 0;
		samples += int(moving.size());
	}
	EXPECT_LE(falseMoving * 1000, samples) << falseMoving << " of " << samples << " board samples moving";
	// The arm: 4 rows, 8 columns from the left edge, at 1700 mm.
	for (int y = 0; y < 30; ++y)
		for (int x = 0; x < 40; ++x)
			noisy(x, y, x < 8 && y >= 13 && y < 17 ? 1700 : 2000);
	background.update(depth, moving);
	int armMoving = 0;
	for (int y = 13; y < 17; ++y)
		for (int x = 0; x < 8; ++x)
			armMoving += moving.at(x, y) != 0;
	// The lecturer picker's least moving pixels (algo/lecturer_picker.hpp).
	std::printf("%d of the arm's 32 pixels moving, %d of %d board samples\n", armMoving, falseMoving, samples);
	EXPECT_GE(armMoving, LecturerPicker::kMinMovingPixels) << "of the arm's 32 pixels";
}

// A lone wild depth (a ToF's flying pixel) far in front of a quiet board
// moves neither itself nor, through the 3x3 mean, its neighbours.
TEST(StaticBackground, AFlyingPixelDoesNotMoveItsNeighbours)
{
	StaticBackground background;
	Gray8Image moving;
	Gray16Image depth(9, 9, 2000);
	for (int i = 0; i < 40; ++i)
		background.update(depth, moving);
	depth.at(4, 4) = 500;
	background.update(depth, moving);
	for (size_t p = 0; p < moving.size(); ++p)
		ASSERT_EQ(moving.data()[p], 0) << "pixel " << p;
}

// The 3x3 test against a floating-point reference: after one frame every
// mean is that frame's depth and every deviation 15/16 of kToleranceMm (it
// starts there and follows the frame's zero deviation by 1/16), so the
// second frame's decision is known in closed form. Excesses stay under one
// pixel's own threshold (150 + 2 x 140.6 mm), so only the box can move a
// pixel. Tolerance: pixels whose float margin is within 1 mm per pixel of
// the box (the Q9 table of 1/sqrt(n), Q3 depths) may go either way; every
// other pixel agrees.
TEST(StaticBackground, TheBoxTestAgreesWithAFloatReference)
{
	std::mt19937 random(5);
	std::uniform_int_distribution<int> board(1950, 2050), excess(100, 420);
	const int w = 32, h = 24;
	Gray16Image first(w, h), second(w, h);
	for (int y = 0; y < h; ++y)
		for (int x = 0; x < w; ++x) {
			first.at(x, y) = uint16_t(board(random));
			// Patches: whole 4x4 blocks near, so the box's mean varies.
			const int block = ((x / 4) * 7 + (y / 4) * 3) % 5;
			second.at(x, y) = uint16_t(first.at(x, y) - (block < 2 ? excess(random) : excess(random) / 4));
		}
	StaticBackground background;
	Gray8Image moving;
	background.update(first, moving);
	background.update(second, moving);
	const double tol = StaticBackground::kToleranceMm;
	int agreed = 0, near = 0, movingCount = 0;
	for (int y = 0; y < h; ++y)
		for (int x = 0; x < w; ++x) {
			double sumExcess = 0;
			int n = 0;
			for (int yy = std::max(0, y - 1); yy <= std::min(h - 1, y + 1); ++yy)
				for (int xx = std::max(0, x - 1); xx <= std::min(w - 1, x + 1); ++xx, ++n)
					sumExcess += double(first.at(xx, yy)) - double(second.at(xx, yy));
			const double deviation = tol * 15.0 / 16.0;
			const double threshold = n * tol + 2.0 * n * deviation / std::sqrt(double(n));
			const double margin = sumExcess - threshold;
			if (std::fabs(margin) <= n) {
				near++;
				continue;
			}
			const bool expected = margin > 0;
			movingCount += expected;
			EXPECT_EQ(moving.at(x, y) != 0, expected) << "pixel " << x << "," << y << " margin " << margin;
			agreed++;
		}
	std::printf("%d pixels agree (%d moving), %d within the tolerance\n", agreed, movingCount, near);
	EXPECT_GT(movingCount, 20);
	EXPECT_GT(agreed - movingCount, 20);
}

TEST(StaticBackground, SomeoneStandingStillFadesIntoTheBackgroundSlowly)
{
	StaticBackground background;
	Gray8Image moving;
	Gray16Image depth(6, 6, 2000);
	background.update(depth, moving);
	depth.at(4, 4) = 1400; // alone: noise, never moving
	for (int y = 1; y < 3; ++y)
		for (int x = 1; x < 3; ++x)
			depth.at(x, y) = 1400; // someone, 2 x 2 pixels
	// 600 mm in front, tolerance 150 + 2 * 150 (the initial deviation): it
	// takes (600 - 450) / kFadeMmPerFrame frames to fade in, not fewer.
	int framesMoving = 0;
	for (int i = 0; i < 400; ++i) {
		background.update(depth, moving);
		framesMoving += moving.at(1, 1) != 0;
		ASSERT_EQ(moving.at(4, 4), 0);
	}
	EXPECT_GE(framesMoving, (600 - 3 * StaticBackground::kToleranceMm) / StaticBackground::kFadeMmPerFrame - 1);
	EXPECT_LT(framesMoving, 400);
}

TEST(Morphology, LabelledComponentsHaveTheirSizesAndOneCanBeKept)
{
	Gray8Image mask(20, 10, 0);
	for (int y = 0; y < 10; ++y)
		for (int x = 0; x < 8; ++x)
			mask.at(x, y) = 255; // 80 pixels
	for (int y = 0; y < 4; ++y)
		for (int x = 12; x < 16; ++x)
			mask.at(x, y) = 255; // 16 pixels
	Gray8Image copy = mask;
	ComponentScratch scratch;
	ASSERT_EQ(labelComponents(copy, scratch), 2); // raster order of first pixels
	EXPECT_EQ(scratch.sizes[0], 80);
	EXPECT_EQ(scratch.sizes[1], 16);
	keepComponent(copy, scratch, 1);
	EXPECT_EQ(copy.at(13, 2), 255);
	EXPECT_EQ(copy.at(3, 3), 0);
	keepComponent(copy, scratch, -1); // none
	EXPECT_EQ(copy.at(13, 2), 0);
}

TEST(DepthSeeder, ADeskLargerThanTheLecturerIsNotTheLecturer)
{
	std::mt19937 random(3);
	DepthSeeder seeder;
	DepthSeeds seeds;
	DepthFrame frame;
	seedEmptyRoom(random, seeder, seeds, frame);
	EXPECT_EQ(seeds.labels.at(35, 25), kTrimapLecturer); // only the desk in range: largest
	room(true, random, frame);
	seeder.seed(frame, seeds);
	EXPECT_EQ(seeds.labels.at(10, 18), kTrimapLecturer);
	EXPECT_EQ(seeds.labels.at(35, 25), kTrimapBoard);
	EXPECT_EQ(seeds.lecturerDepthMm, 1400);
}

TEST(DepthSeeder, AnArmThinnerThanTheErosionIsStillSeeded)
{
	std::mt19937 random(4);
	DepthSeeder seeder;
	DepthSeeds seeds;
	DepthFrame frame;
	seedEmptyRoom(random, seeder, seeds, frame);
	// Only an arm, 2 pixels thick, reaches into view: the erosion leaves
	// nothing of it, and the desk would be the only in-range area left.
	room(false, random, frame);
	for (int x = 0; x < 12; ++x)
		for (int y = 8; y < 10; ++y)
			frame.depthMm.at(x, y) = 1400;
	seeder.seed(frame, seeds);
	EXPECT_EQ(seeds.labels.at(6, 8), kTrimapSubset); // lecturer colours, but too thin for a core
	EXPECT_EQ(seeds.labels.at(6, 11), kTrimapUndecided);
	EXPECT_EQ(seeds.labels.at(35, 25), kTrimapBoard); // not the desk
	EXPECT_EQ(seeds.lecturerDepthMm, 1400);

	// The whole lecturer in view with a 1-pixel arm stretched out: the body
	// is the subset, the arm (gone in the eroded mask) lies in the band.
	room(true, random, frame);
	for (int x = 15; x < 25; ++x)
		frame.depthMm.at(x, 12) = 1400;
	seeder.seed(frame, seeds);
	EXPECT_EQ(seeds.labels.at(10, 18), kTrimapLecturer);
	EXPECT_EQ(seeds.labels.at(24, 12), kTrimapInRange);   // in range, eroded away
	EXPECT_EQ(seeds.labels.at(26, 12), kTrimapUndecided); // dilated beyond its end
	EXPECT_EQ(seeds.labels.at(27, 12), kTrimapBoard);
}

TEST(Morphology, ComponentsTouchingSeedsAreKeptTheRestDropped)
{
	Gray8Image mask(12, 6, 0), seeds(12, 6, 0);
	for (int x = 0; x < 4; ++x)
		mask.at(x, 1) = 255; // component A: 4 pixels
	for (int y = 0; y < 6; ++y)
		mask.at(6, y) = 255; // component B: 6 pixels
	mask.at(10, 3) = mask.at(11, 3) = mask.at(11, 4) = 255; // component C: 3 pixels
	seeds.at(2, 1) = seeds.at(11, 4) = 255;                  // in A and C
	seeds.at(8, 0) = 255;                                     // outside every component
	ComponentScratch scratch;
	EXPECT_EQ(keepComponentsTouching(mask, seeds, scratch), 7);
	EXPECT_EQ(mask.at(0, 1), 255);
	EXPECT_EQ(mask.at(10, 3), 255);
	EXPECT_EQ(mask.at(6, 2), 0);
	EXPECT_EQ(mask.at(8, 0), 0);
}

// The boxes summed by rows (StaticBackground::poolBoxes) against the box
// summed afresh per pixel, as before issue 28: equal bit for bit, moving
// and the learned means, frame after frame, on noisy rooms with holes (no
// measurement), flying pixels, a lecturer walking across, and tiny images
// whose boxes are cut by every border.
TEST(StaticBackground, RowSummedBoxesEqualThePerPixelBoxesBitForBit)
{
	const int sizes[][2] = { { 160, 124 }, { 37, 23 }, { 1, 1 }, { 2, 5 }, { 7, 1 }, { 1, 9 } };
	for (const auto &size : sizes) {
		const int w = size[0], h = size[1];
		std::mt19937 random(uint32_t(w * 131 + h));
		std::uniform_int_distribution<int> noise(-90, 90), wild(0, 9000), pick(0, 99);
		StaticBackground fast;
		test::StaticBackgroundPerPixelBox reference;
		Gray8Image movingFast, movingReference;
		Gray16Image depth(w, h);
		for (int frame = 0; frame < 60; ++frame) {
			const int lecturerX = frame * w / 60;
			for (int y = 0; y < h; ++y)
				for (int x = 0; x < w; ++x) {
					const int p = pick(random);
					int z = 2000 + noise(random) * (x < w / 4 ? 3 : 1);
					if (std::abs(x - lecturerX) < 3 + frame % 5)
						z = 1400 + noise(random);
					depth.at(x, y) = uint16_t(p < 4 ? 0 : p < 6 ? wild(random) : z);
				}
			fast.update(depth, movingFast);
			reference.update(depth, movingReference);
			for (size_t i = 0; i < size_t(w) * h; ++i) {
				ASSERT_EQ(movingFast.data()[i], movingReference.data()[i])
					<< w << "x" << h << " frame " << frame << " pixel " << i;
				ASSERT_EQ(fast.meanMm(i), reference.meanMm(i)) << w << "x" << h << " frame " << frame << " pixel " << i;
			}
		}
	}
}
