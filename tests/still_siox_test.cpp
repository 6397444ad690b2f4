// SIOX on still images with a known answer: depthkey's fixed-point SIOX
// against the truth and against the double SIOX 1.13 reference
// (tests/siox_reference.hpp) on trimaps shaped like depth seeds; the
// post-processing rules. The depthkey-siox tool end to end is
// tests/process/siox_tool_test.cpp.
#include "algo/still_siox.hpp"
#include "hal/image_file.hpp"
#include "tests/siox_reference.hpp"
#include "tests/synthetic_still.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <unistd.h>

using namespace depthkey;
using namespace depthkey::test;

TEST(StillSiox, AtLeastAsAccurateAsTheReferenceOnDepthSeedTrimaps)
{
	StillSiox siox;
	double sumOurs = 0, sumRef = 0;
	int images = 0;
	for (int band : { 5, 10, 20 }) {
		for (uint32_t seed : { 1u, 2u, 3u }) {
			SyntheticStill s = makeStill(320, 240, band, seed);
			Gray8Image mask, alpha;
			ASSERT_EQ(siox.segment(s.image, s.trimap, mask, alpha), 0);
			Gray8Image ref = referenceSegmentate(s.image, s.trimap);
			double ours = intersectionOverUnion(mask, s.truth), theirs = intersectionOverUnion(ref, s.truth);
			std::printf("band %2d seed %u: IoU depthkey %.4f, reference SIOX 1.13 %.4f\n", band, seed, ours, theirs);
			EXPECT_GE(ours, 0.97);
			sumOurs += ours;
			sumRef += theirs;
			++images;
		}
	}
	std::printf("mean IoU over %d images: depthkey %.4f, reference %.4f\n", images, sumOurs / images, sumRef / images);
	EXPECT_GE(sumOurs / images, sumRef / images);
}

TEST(StillSiox, SeedsAreNeverContradicted)
{
	// Random colours and a random trimap: whatever SIOX decides, surely
	// lecturer stays 255 and surely board stays 0.
	std::mt19937 rng(4);
	std::uniform_int_distribution<int> byte(0, 255), label(0, 2);
	RgbImage image(64, 48);
	Gray8Image trimap(64, 48), mask, alpha;
	for (size_t i = 0; i < image.size(); ++i) {
		image.data()[i] = { uint8_t(byte(rng)), uint8_t(byte(rng)), uint8_t(byte(rng)) };
		int l = label(rng);
		trimap.data()[i] = l == 0 ? kTrimapBoard : l == 1 ? kTrimapLecturer : uint8_t(1 + byte(rng) % 254);
	}
	StillSiox siox;
	ASSERT_EQ(siox.segment(image, trimap, mask, alpha), 0);
	for (size_t i = 0; i < trimap.size(); ++i) {
		if (trimap.data()[i] == kTrimapLecturer) {
			ASSERT_EQ(alpha.data()[i], 255) << i;
		}
		if (trimap.data()[i] == kTrimapBoard) {
			ASSERT_EQ(alpha.data()[i], 0) << i;
		}
		ASSERT_EQ(mask.data()[i], alpha.data()[i] >= 128 ? 255 : 0);
	}
}

namespace {

// A body seed and a hand seed, joined only through the undecided band; the
// band is lecturer-coloured except the wrist, which looks like the board.
struct HandScene {
	RgbImage image{ 120, 60, Rgb8{ 30, 60, 40 } };
	Gray8Image trimap{ 120, 60, kTrimapBoard };
};

HandScene handScene()
{
	HandScene s;
	const Rgb8 shirt{ 150, 40, 50 };
	for (int y = 10; y < 50; ++y)
		for (int x = 10; x < 110; ++x) {
			s.trimap.at(x, y) = kTrimapUndecided;
			bool wrist = x >= 68 && x < 72;
			bool lecturer = (x >= 14 && x < 60 && y >= 14 && y < 46) ||        // body and its edge
					(x >= 60 && x < 80 && y >= 28 && y < 32 && !wrist) || // forearm, cut at the wrist
					(x >= 80 && x < 100 && y >= 20 && y < 40);            // hand
			if (lecturer)
				s.image.at(x, y) = shirt;
		}
	for (int y = 18; y < 42; ++y)
		for (int x = 18; x < 56; ++x)
			s.trimap.at(x, y) = kTrimapLecturer; // body seed
	for (int y = 26; y < 34; ++y)
		for (int x = 86; x < 94; ++x)
			s.trimap.at(x, y) = kTrimapLecturer; // hand seed
	// Lecturer-coloured clutter in the band touching no seed: dropped.
	for (int y = 44; y < 48; ++y)
		for (int x = 96; x < 104; ++x)
			s.image.at(x, y) = shirt;
	return s;
}

} // namespace

TEST(StillSiox, HandBehindAnUndecidedWristSurvivesAndStrayBlobsGo)
{
	HandScene s = handScene();
	StillSiox siox;
	Gray8Image mask, alpha;
	ASSERT_EQ(siox.segment(s.image, s.trimap, mask, alpha), 0);
	EXPECT_EQ(mask.at(82, 22), 255);  // hand edge, undecided, beyond the wrist
	EXPECT_EQ(mask.at(98, 38), 255);
	EXPECT_EQ(mask.at(70, 30), 0);    // the wrist looks like board
	EXPECT_EQ(mask.at(15, 15), 255);  // body edge
	EXPECT_EQ(mask.at(100, 46), 0);   // stray lecturer-coloured blob, no seed
	EXPECT_EQ(mask.at(105, 15), 0);   // band board
}

TEST(StillSiox, EnclosedHoleWithoutBoardSeedIsFilledOneWithASeedStays)
{
	// The first hole is a shadow on the shirt, a colour a third of the way
	// from the board's to the shirt's: SIOX calls it board, but not
	// clearly, so enclosed by the lecturer it is filled.
	const Rgb8 shirt{ 150, 40, 50 }, board{ 30, 60, 40 }, shadow{ 70, 53, 43 };
	RgbImage image(60, 40, board);
	Gray8Image trimap(60, 40, kTrimapBoard), mask, alpha;
	for (int y = 5; y < 35; ++y)
		for (int x = 5; x < 55; ++x) {
			trimap.at(x, y) = kTrimapLecturer;
			image.at(x, y) = shirt;
		}
	// Two board-coloured undecided holes inside the lecturer seed; the
	// second has a surely-board pixel in it (board seen through the arm).
	for (int y = 12; y < 20; ++y)
		for (int x = 10; x < 18; ++x) {
			trimap.at(x, y) = kTrimapUndecided;
			image.at(x, y) = shadow;
			trimap.at(x + 25, y) = kTrimapUndecided;
			image.at(x + 25, y) = board;
		}
	trimap.at(39, 16) = kTrimapBoard;
	StillSiox siox;
	ASSERT_EQ(siox.segment(image, trimap, mask, alpha), 0);
	EXPECT_EQ(mask.at(14, 16), 255);
	EXPECT_EQ(mask.at(38, 16), 0);
	EXPECT_EQ(mask.at(39, 16), 0);
}

TEST(StillSiox, AnEnclosedHoleTheEvidenceCallsBoardClearlyStaysBoard)
{
	// The board seen between an arm and the body: enclosed by the lecturer,
	// with no board seed in it, but of the board's own colour.
	const Rgb8 shirt{ 150, 40, 50 }, board{ 30, 60, 40 };
	RgbImage image(60, 40, board);
	Gray8Image trimap(60, 40, kTrimapBoard), mask, alpha;
	for (int y = 5; y < 35; ++y)
		for (int x = 5; x < 55; ++x) {
			const bool hole = y >= 12 && y < 20 && x >= 10 && x < 18;
			trimap.at(x, y) = hole ? kTrimapUndecided : kTrimapLecturer;
			image.at(x, y) = hole ? board : shirt;
		}
	StillSiox siox;
	ASSERT_EQ(siox.segment(image, trimap, mask, alpha), 0);
	EXPECT_EQ(mask.at(14, 16), 0);
	EXPECT_EQ(mask.at(30, 16), 255);
}

TEST(StillSiox, RefusesMismatchedSizesAndTrimapsWithoutBoard)
{
	StillSiox siox;
	RgbImage image(10, 10);
	Gray8Image trimap(9, 10), mask, alpha;
	EXPECT_EQ(siox.segment(image, trimap, mask, alpha), -EINVAL);
	Gray8Image allLecturer(10, 10, kTrimapLecturer);
	EXPECT_EQ(siox.segment(image, allLecturer, mask, alpha), -ENODATA);
}

TEST(StillSiox, ALargeLecturerRegionCutOffByBoardColouredClothesStays)
{
	// A body seed in a dark vest the colour of the board; beside it, in the
	// band, a white sleeve (30 x 20 = 600 pixels) that touches the body only
	// through the vest, and a small white blob (6 x 6) touching nothing.
	const Rgb8 board{ 30, 60, 40 }, sleeve{ 220, 220, 215 };
	RgbImage image(160, 100, board);
	Gray8Image trimap(160, 100, kTrimapBoard);
	for (int y = 10; y < 90; ++y)
		for (int x = 10; x < 150; ++x)
			trimap.at(x, y) = kTrimapUndecided;
	for (int y = 30; y < 70; ++y)
		for (int x = 20; x < 50; ++x) {
			trimap.at(x, y) = kTrimapLecturer; // body seed: shirt in the middle, vest around
			if (x >= 28 && x < 42)
				image.at(x, y) = sleeve;
		}
	for (int y = 40; y < 60; ++y)
		for (int x = 56; x < 86; ++x)
			image.at(x, y) = sleeve; // the sleeve, 6 pixels of vest-coloured band from the body
	for (int y = 70; y < 76; ++y)
		for (int x = 120; x < 126; ++x)
			image.at(x, y) = sleeve; // a blob of chalk
	StillSiox siox;
	Gray8Image mask, alpha;
	ASSERT_EQ(siox.segment(image, trimap, mask, alpha), 0);
	EXPECT_EQ(mask.at(53, 50), 0);   // the vest-coloured gap
	EXPECT_EQ(mask.at(70, 50), 255); // the sleeve stays
	EXPECT_EQ(mask.at(122, 72), 0);  // the small blob goes
}
