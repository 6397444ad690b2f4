// The per-pixel board model: learned only where the trimap says surely
// board, kept behind the lecturer, following written ink, and matched after
// a change of the room light.
#include <gtest/gtest.h>

#include "algo/board_model.hpp"

using namespace depthkey;

namespace {

// Enough frames for every row to be visited `visits` times.
void learnFrames(BoardModel &model, const RgbImage &colour, const Gray8Image &trimap, int visits)
{
	for (int i = 0; i < visits * BoardModel::kRowStride; ++i)
		model.learn(colour, trimap);
}

} // namespace

TEST(BoardModel, LearnsSurelyBoardPixelsOnlyAndKeepsThemBehindTheLecturer)
{
	const Rgb8 board{ 30, 60, 40 }, shirt{ 220, 220, 215 };
	RgbImage colour(32, 24, board);
	Gray8Image trimap(32, 24, kTrimapBoard);
	BoardModel model;
	learnFrames(model, colour, trimap, 3);
	EXPECT_EQ(model.distance(10, 10, board), 0);
	// The lecturer steps in front of the left half: those pixels are not
	// learned, and the model there still says how the board looked.
	for (int y = 0; y < 24; ++y)
		for (int x = 0; x < 16; ++x) {
			colour.at(x, y) = shirt;
			trimap.at(x, y) = kTrimapUndecided;
		}
	learnFrames(model, colour, trimap, 8);
	EXPECT_EQ(model.distance(5, 10, board), 0);
	EXPECT_GT(model.distance(5, 10, shirt), 400);
	// Never seen as board: no model.
	BoardModel fresh;
	fresh.learn(colour, trimap);
	EXPECT_EQ(fresh.distance(5, 0, board), -1);
}

TEST(BoardModel, FollowsInkWrittenOnTheBoard)
{
	const Rgb8 board{ 30, 60, 40 }, chalk{ 235, 235, 230 };
	RgbImage colour(16, 16, board);
	Gray8Image trimap(16, 16, kTrimapBoard);
	BoardModel model;
	learnFrames(model, colour, trimap, 3);
	colour.at(8, 8) = chalk;
	learnFrames(model, colour, trimap, 24); // 24 visits at 1/4: 0.75^24 of 200 levels left
	EXPECT_LE(model.distance(8, 8, chalk), 6);
	EXPECT_GT(model.distance(8, 8, board), 400);
}

TEST(BoardModel, AGlobalChangeOfLightStillMatches)
{
	const Rgb8 board{ 40, 80, 60 }, dimmer{ 34, 68, 51 }; // 15 % less light
	RgbImage colour(32, 32, board);
	Gray8Image trimap(32, 32, kTrimapBoard);
	BoardModel model;
	learnFrames(model, colour, trimap, 3);
	// A lecturer covers one corner; the light dims everywhere.
	for (int y = 0; y < 32; ++y)
		for (int x = 0; x < 32; ++x)
			colour.at(x, y) = dimmer;
	for (int y = 0; y < 8; ++y)
		for (int x = 0; x < 8; ++x)
			trimap.at(x, y) = kTrimapLecturer;
	model.learn(colour, trimap);
	// Behind him the model is as it was, but compared after the gain the
	// dimmer board there still matches.
	EXPECT_LE(model.distance(2, 2, dimmer), 3);
	EXPECT_NEAR(model.gainQ8()[1], 256 * 68 / 80, 3);
}
