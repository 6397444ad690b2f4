// StaticBackground and the depth seeder's use of it: a desk standing in the
// lecturer's depth interval (larger than him) is furniture; the lecturer who
// steps in front of the board is the lecturer.

#include "algo/depth_seeder.hpp"
#include "algo/morphology.hpp"
#include "algo/static_background.hpp"
#include "algo/trimap.hpp"

#include <gtest/gtest.h>

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
