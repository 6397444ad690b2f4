// The board predicted from its own picture (algo/board_picture_prior.hpp):
// the fixed-point prediction against a double reference (the gain as the
// ratio of sums, the colour as picture x gain; tolerance 1 level), the map
// through H, and the board model taught it: a stroke written behind the
// lecturer, never seen by the camera, matches the model at once.
#include "algo/board_model.hpp"
#include "algo/board_picture_prior.hpp"
#include "algo/changed_rows.hpp"
#include "algo/trimap.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

using namespace depthkey;

namespace {

constexpr int kW = 64, kH = 48;

// A board picture twice the colour size: colour (x, y) sees board (2x, 2y).
Homography doubling()
{
	Homography h;
	h.h = { 2, 0, 0, 0, 2, 0, 0, 0, 1 };
	return h;
}

RgbImage boardPicture(uint64_t seed, int w = kW, int h = kH)
{
	RgbImage picture(2 * w, 2 * h);
	uint64_t s = seed;
	for (int y = 0; y < picture.height(); ++y)
		for (int x = 0; x < picture.width(); ++x) {
			s = s * 6364136223846793005ull + 1442695040888963407ull;
			// A dark green board with some chalk.
			const bool chalk = (s >> 60) == 0;
			picture.row(y)[x] = chalk ? Rgb8{ 230, 230, 220 }
						  : Rgb8{ uint8_t(20 + (s >> 58) % 8), uint8_t(60 + (s >> 50) % 8), uint8_t(40 + (s >> 40) % 8) };
		}
	return picture;
}

// What the camera sees of the empty board: the picture under each pixel
// times a light of (0.8, 0.9, 1.1).
RgbImage cameraView(const RgbImage &picture)
{
	const int w = picture.width() / 2, h = picture.height() / 2;
	RgbImage colour(w, h);
	for (int y = 0; y < h; ++y)
		for (int x = 0; x < w; ++x) {
			const Rgb8 p = picture.row(2 * y)[2 * x];
			colour.row(y)[x] = { uint8_t(std::lround(p.r * 0.8)), uint8_t(std::lround(p.g * 0.9)),
					     uint8_t(std::min(255L, std::lround(p.b * 1.1))) };
		}
	return colour;
}

} // namespace

namespace {

// At kW x kH the gain is fitted on every 4th row; wider frames fit on a
// sparser grid (rows and columns), so that its cost stays what it is at
// 640 pixels wide.
void expectPredictionWithinOneLevel(int kW, int kH)
{
	const RgbImage picture = boardPicture(1, kW, kH);
	const RgbImage colour = cameraView(picture);
	BoardModel model;
	model.learn(colour, Gray8Image(kW, kH, kTrimapBoard));
	for (int i = 0; i < BoardModel::kRowStride * BoardModel::kLearnedVisits; ++i)
		model.learn(colour, Gray8Image(kW, kH, kTrimapBoard));

	BoardPicturePrior prior;
	ASSERT_EQ(prior.configure(kW, kH, doubling(), RadialLens{}, 2 * kW, 2 * kH), 0);
	ASSERT_TRUE(prior.predict(picture, colour, model));

	// The double reference: the gain is the ratio of the sums over the
	// pixels that match the model (all of them here) on the grid it
	// measures on.
	double sumC[3] = {}, sumP[3] = {};
	for (int y = 0; y < kH; y += prior.fitRowStep())
		for (int x = 0; x < kW; x += prior.fitColumnStep()) {
			const Rgb8 c = colour.row(y)[x], p = picture.row(2 * y)[2 * x];
			sumC[0] += c.r, sumC[1] += c.g, sumC[2] += c.b;
			sumP[0] += p.r, sumP[1] += p.g, sumP[2] += p.b;
		}
	int worst = 0;
	for (int y = 0; y < kH; ++y)
		for (int x = 0; x < kW; ++x) {
			ASSERT_EQ(prior.onDisplay().row(y)[x], kTrimapBoard);
			const Rgb8 p = picture.row(2 * y)[2 * x], got = prior.predictedAt(x, y);
			const double want[3] = { std::min(255.0, p.r * sumC[0] / sumP[0]),
						 std::min(255.0, p.g * sumC[1] / sumP[1]),
						 std::min(255.0, p.b * sumC[2] / sumP[2]) };
			const int g[3] = { got.r, got.g, got.b };
			for (int k = 0; k < 3; ++k)
				worst = std::max(worst, int(std::lround(std::fabs(g[k] - want[k]) + 0.49)));
		}
	std::printf("    prediction at %dx%d (fit every %d rows, %d columns), fixed vs double: worst %d level(s)\n", kW, kH,
		    prior.fitRowStep(), prior.fitColumnStep(), worst);
	EXPECT_LE(worst, 1);
	EXPECT_NEAR(prior.gainQ8()[0], 0.8 * 256, 3);
	EXPECT_NEAR(prior.gainQ8()[2], 1.1 * 256, 3);
}

} // namespace

TEST(BoardPicturePrior, PredictsTheCameraColourWithinOneLevelOfTheDoubleReference)
{
	expectPredictionWithinOneLevel(kW, kH);
	expectPredictionWithinOneLevel(1300, 40); // fitted every 8th row, every 2nd column
}

TEST(BoardPicturePrior, OffThePictureIsOffTheDisplayAndNothingWithoutALearnedBoard)
{
	Homography shifted = doubling();
	shifted.h[2] = -40; // colour x < 20 maps left of the picture
	BoardPicturePrior prior;
	ASSERT_EQ(prior.configure(kW, kH, shifted, RadialLens{}, 2 * kW, 2 * kH), 0);
	EXPECT_EQ(prior.onDisplay().row(10)[5], kTrimapLecturer) << "left of the picture";
	EXPECT_EQ(prior.onDisplay().row(10)[30], kTrimapBoard);
	const RgbImage picture = boardPicture(2);
	BoardModel unlearned;
	unlearned.learn(cameraView(picture), Gray8Image(kW, kH, kTrimapLecturer)); // nothing is board
	EXPECT_FALSE(prior.predict(picture, cameraView(picture), unlearned)) << "no gain can be measured";
	EXPECT_FALSE(prior.predict(RgbImage(10, 10), cameraView(picture), unlearned)) << "another picture size";
	EXPECT_EQ(prior.configure(0, kH, shifted, RadialLens{}, 2 * kW, 2 * kH), -EINVAL);
	EXPECT_FALSE(prior.configured());
}

// The reason for it all: the lecturer stood in front of this part of the
// board while a stroke appeared there. The camera never saw the stroke, so
// the learned model still holds the empty board; taught the prediction, the
// model knows the stroke before he steps away.
TEST(BoardPicturePrior, AStrokeWrittenBehindTheLecturerIsKnownBeforeItIsSeen)
{
	RgbImage picture = boardPicture(3);
	const RgbImage colour = cameraView(picture);
	BoardModel model;
	for (int i = 0; i < BoardModel::kRowStride * 3; ++i)
		model.learn(colour, Gray8Image(kW, kH, kTrimapBoard));
	// He covers x 20..29; a chalk stroke appears at row 24 under him.
	Gray8Image covered(kW, kH, kTrimapBoard);
	for (int y = 0; y < kH; ++y)
		for (int x = 20; x < 30; ++x)
			covered.row(y)[x] = kTrimapLecturer;
	for (int x = 40; x < 60; ++x)
		picture.row(48)[x] = Rgb8{ 230, 230, 220 };
	const Rgb8 strokeSeen = cameraView(picture).row(24)[25];
	EXPECT_GT(model.distance(25, 24, strokeSeen), 100) << "the learned model alone: empty board there";

	BoardPicturePrior prior;
	ASSERT_EQ(prior.configure(kW, kH, doubling(), RadialLens{}, 2 * kW, 2 * kH), 0);
	// 20 teachings of the stroke's row: teach() visits a row every
	// kTeachRowStride-th frame.
	for (int frame = 0; frame < 20 * BoardModel::kTeachRowStride; ++frame) {
		model.learn(colour, covered); // the camera still sees him there
		ASSERT_TRUE(prior.predict(picture, colour, model));
		model.teach(prior.sampled(), prior.gainQ8(), prior.onDisplay());
	}
	EXPECT_LE(model.distance(25, 24, strokeSeen), 12) << "taught: the stroke is board";
	EXPECT_LE(model.distance(5, 5, colour.row(5)[5]), 6) << "the board elsewhere still matches";
}

TEST(ChangedRows, TheFirstAndLastRowThatDifferOrNone)
{
	const RgbImage before = boardPicture(5);
	RgbImage now = before;
	EXPECT_TRUE(changedRows(before, now).empty());
	now.row(17)[3] = Rgb8{ 1, 2, 3 };
	EXPECT_EQ(changedRows(before, now).first, 17);
	EXPECT_EQ(changedRows(before, now).last, 17);
	now.row(60)[now.width() - 1] = Rgb8{ 4, 5, 6 };
	EXPECT_EQ(changedRows(before, now).first, 17);
	EXPECT_EQ(changedRows(before, now).last, 60);
	const RowRange all = changedRows(before, RgbImage(4, 3));
	EXPECT_EQ(all.first, 0);
	EXPECT_EQ(all.last, 2);
}

TEST(BoardPicturePrior, RowsChangedInPlaceAreSampledAgainAsAWholeSamplingWould)
{
	// A slanted view: each colour row sees several picture rows.
	Homography slanted;
	slanted.h = { 1.8, 0.3, 2, 0.25, 1.7, 1, 0, 0, 1 };
	RgbImage picture = boardPicture(7);
	const RgbImage colour = cameraView(picture);
	BoardModel model;
	model.learn(colour, Gray8Image(kW, kH, kTrimapBoard));
	auto fresh = [&](const RgbImage &p) {
		BoardPicturePrior whole;
		EXPECT_EQ(whole.configure(kW, kH, slanted, RadialLens{}, 2 * kW, 2 * kH), 0);
		whole.predict(p, colour, model);
		return whole.sampled();
	};
	BoardPicturePrior prior;
	ASSERT_EQ(prior.configure(kW, kH, slanted, RadialLens{}, 2 * kW, 2 * kH), 0);
	prior.predict(picture, colour, model);
	ASSERT_EQ(prior.sampled(), fresh(picture));

	// Strokes in two bands of rows, told as they come, sampled at the next
	// predict(): exactly what sampling the whole new picture gives.
	RgbImage before = picture;
	for (int x = 10; x < 90; ++x)
		picture.row(30)[x] = picture.row(31)[x] = Rgb8{ 230, 230, 220 };
	RowRange changed = changedRows(before, picture);
	prior.pictureRowsChanged(changed.first, changed.last);
	before = picture;
	for (int x = 20; x < 40; ++x)
		picture.row(70)[x] = Rgb8{ 200, 40, 40 };
	changed = changedRows(before, picture);
	prior.pictureRowsChanged(changed.first, changed.last);
	prior.predict(picture, colour, model);
	EXPECT_EQ(prior.sampled(), fresh(picture));

	// Rows said unchanged are not read again (the saving): a stroke not
	// told is not in the prediction until the picture is sampled anew.
	for (int x = 0; x < 2 * kW; ++x)
		picture.row(50)[x] = Rgb8{ 255, 255, 0 };
	prior.pictureRowsChanged(1, 0);
	prior.predict(picture, colour, model);
	EXPECT_NE(prior.sampled(), fresh(picture));
	prior.pictureChanged();
	prior.predict(picture, colour, model);
	EXPECT_EQ(prior.sampled(), fresh(picture));
}
