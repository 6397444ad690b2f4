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

// distance() looks the gained model up in tables (issue 28): it must equal
// the multiply it replaced, (model * gain + 128) >> 8 per channel, at every
// gain learn() and teach() can set (128..512 Q8) and every model value.
TEST(BoardModel, DistanceEqualsTheGainMultiplyItTabulates)
{
	auto multiplied = [](const BoardModel &model, int x, int y, Rgb8 c) {
		const Rgba8 m = model.row(y)[x];
		if (m.a < BoardModel::kLearnedVisits)
			return -1;
		const int *g = model.gainQ8();
		return std::abs(int(c.r) - ((m.r * g[0] + 128) >> 8)) + std::abs(int(c.g) - ((m.g * g[1] + 128) >> 8)) +
		       std::abs(int(c.b) - ((m.b * g[2] + 128) >> 8));
	};
	// A board of every code value (256 columns, each channel a different
	// ramp), learned under steady light.
	RgbImage colour(256, 8);
	Gray8Image trimap(256, 8, kTrimapBoard);
	for (int y = 0; y < 8; ++y)
		for (int x = 0; x < 256; ++x)
			colour.at(x, y) = { uint8_t(x), uint8_t(255 - x), uint8_t((x * 7) & 255) };
	BoardModel model;
	learnFrames(model, colour, trimap, 3);
	// Light scaled by each of a spread of factors (the gain clamps at 128
	// and 512), then the pictures teach() predicts at other gains.
	size_t compared = 0;
	auto compareAll = [&] {
		for (int y = 0; y < 8; ++y)
			for (int x = 0; x < 256; ++x)
				for (Rgb8 c : { Rgb8{ 0, 0, 0 }, Rgb8{ 255, 255, 255 }, colour.at(x, y), Rgb8{ 17, 200, 99 } }) {
					ASSERT_EQ(model.distance(x, y, c), multiplied(model, x, y, c)) << x << "," << y;
					++compared;
				}
	};
	for (int scaleQ8 : { 256, 40, 128, 200, 300, 511, 700, 1000 }) {
		RgbImage lit(256, 8);
		const int gain[3] = { scaleQ8, scaleQ8, scaleQ8 };
		for (int y = 0; y < 8; ++y)
			for (int x = 0; x < 256; ++x)
				lit.at(x, y) = BoardModel::scaleQ8(colour.at(x, y), gain);
		model.learn(lit, trimap);
		compareAll();
		const int taught[3] = { scaleQ8, 256, 512 };
		model.teach(colour, taught, trimap);
		compareAll();
	}
	EXPECT_GT(model.gainQ8()[0], 256); // the gains did move
	EXPECT_GT(compared, 100000u);
}
