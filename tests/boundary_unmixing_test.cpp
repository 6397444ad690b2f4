// The edge unmixing (algo/boundary_unmixing.hpp): against a double
// reference of the same projection (tolerance: none, the integer sums are
// exact where the board model is learned and the light has not changed),
// and its rules: it grows the edge to where the colour puts the silhouette,
// never shrinks it, never leaves the superset, and leaves alike colours be;
// and equal, bit for bit, to the whole-ROI unmixing it replaced (issue 28)
// on lecture frames.
#include <gtest/gtest.h>

#include "algo/boundary_unmixing.hpp"
#include "tests/boundary_unmixing_whole_roi.hpp"
#include "tests/simd_paths.hpp"
#include "tests/edge_scenes.hpp"

#include <cmath>
#include <random>

using namespace depthkey;

namespace {

void learnBoard(BoardModel &model, const RgbImage &board, int visits)
{
	const Gray8Image everywhere(board.width(), board.height(), kTrimapBoard);
	for (int i = 0; i < visits * BoardModel::kRowStride; ++i)
		model.learn(board, everywhere);
}

// The unmixing in doubles, written from the header's formula: board B from
// `board` (the learned model, no gain), F the mean of the lecturer's
// interior within the window, kPasses passes growing the edge.
void referenceUnmix(const RgbImage &colour, const RgbImage &board, const Gray8Image &trimap, int minContrast2,
		    Gray8Image &matte)
{
	const int w = matte.width(), h = matte.height(), r = BoundaryUnmixing::kWindowRadius;
	auto lect = [&](const Gray8Image &m, int x, int y) { return x >= 0 && y >= 0 && x < w && y < h && m.at(x, y); };
	for (int pass = 0; pass < BoundaryUnmixing::kPasses; ++pass) {
		const Gray8Image before = matte;
		auto inside = [&](int x, int y, bool lecturer) {
			for (auto [dx, dy] : { std::pair{ 0, 0 }, { -1, 0 }, { 1, 0 }, { 0, -1 }, { 0, 1 } })
				if (lect(before, x + dx, y + dy) != lecturer)
					return false;
			return true;
		};
		for (int y = 0; y < h; ++y)
			for (int x = 0; x < w; ++x) {
				if (before.at(x, y) || inside(x, y, false) || trimap.at(x, y) == kTrimapBoard)
					continue;
				double f[3] = { 0, 0, 0 };
				int n = 0, boardNear = 0;
				for (int wy = std::max(0, y - r); wy <= std::min(h - 1, y + r); ++wy)
					for (int wx = std::max(0, x - r); wx <= std::min(w - 1, x + r); ++wx) {
						if (inside(wx, wy, true)) {
							const Rgb8 c = colour.at(wx, wy);
							f[0] += c.r, f[1] += c.g, f[2] += c.b, ++n;
						} else if (inside(wx, wy, false)) {
							++boardNear;
						}
					}
				if (n == 0 || boardNear == 0)
					continue;
				const Rgb8 b = board.at(x, y), i = colour.at(x, y);
				const double bl[3] = { double(b.r), double(b.g), double(b.b) };
				const double il[3] = { double(i.r), double(i.g), double(i.b) };
				double dot = 0, norm = 0;
				for (int c = 0; c < 3; ++c) {
					const double d = f[c] / n - bl[c];
					norm += d * d;
					dot += (il[c] - bl[c]) * d;
				}
				if (norm >= minContrast2 && dot / norm >= 0.5)
					matte.at(x, y) = 255;
			}
	}
}

// A vertical edge: lecturer (60, 60, 60) left of column 20, board (20, 20,
// 20); column 20 is 70 % lecturer, column 21 30 %. The decision starts two
// columns inside him.
struct StraightEdge {
	static constexpr int kW = 40, kH = 16;
	RgbImage board{ kW, kH, Rgb8{ 20, 20, 20 } }, colour{ kW, kH, Rgb8{ 20, 20, 20 } };
	Gray8Image trimap{ kW, kH, kTrimapUndecided }, matte{ kW, kH, 0 };
	StraightEdge(uint8_t lecturerLevel = 60)
	{
		const int l = lecturerLevel;
		for (int y = 0; y < kH; ++y) {
			for (int x = 0; x < 20; ++x)
				colour.at(x, y) = Rgb8{ uint8_t(l), uint8_t(l), uint8_t(l) };
			const uint8_t mix70 = uint8_t(std::lround(0.7 * l + 0.3 * 20)), mix30 = uint8_t(std::lround(0.3 * l + 0.7 * 20));
			colour.at(20, y) = Rgb8{ mix70, mix70, mix70 };
			colour.at(21, y) = Rgb8{ mix30, mix30, mix30 };
			for (int x = 0; x < 18; ++x)
				matte.at(x, y) = 255;
		}
	}
	int lastLecturerColumn(int y) const
	{
		int last = -1;
		for (int x = 0; x < kW; ++x)
			if (matte.at(x, y))
				last = x;
		return last;
	}
};

} // namespace

TEST(BoundaryUnmixing, AgreesWithTheDoubleReferenceOnANoisyDisc)
{
	const int w = 96, h = 72;
	std::mt19937 rng(7);
	std::normal_distribution<double> noise(0.0, 3.0);
	auto level = [&](double v) { return uint8_t(std::clamp(std::lround(v + noise(rng)), 0L, 255L)); };
	RgbImage board(w, h), colour(w, h);
	Gray8Image trimap(w, h, kTrimapUndecided), matte(w, h, 0);
	for (int y = 0; y < h; ++y)
		for (int x = 0; x < w; ++x) {
			// A dark board with a lighter stroke; a dull red sleeve.
			const bool stroke = (x + 2 * y) % 23 < 2;
			const double b[3] = { stroke ? 120.0 : 28, stroke ? 120.0 : 32, stroke ? 120.0 : 30 };
			board.at(x, y) = Rgb8{ level(b[0]), level(b[1]), level(b[2]) };
			// Coverage of a disc of radius 20, by 4x4 supersampling.
			int covered = 0;
			for (int s = 0; s < 16; ++s) {
				const double px = x + (s % 4 + 0.5) / 4 - 48, py = y + (s / 4 + 0.5) / 4 - 36;
				covered += px * px + py * py < 400;
			}
			const double a = covered / 16.0;
			const Rgb8 bb = board.at(x, y);
			colour.at(x, y) = Rgb8{ level(a * 70 + (1 - a) * bb.r), level(a * 40 + (1 - a) * bb.g),
						level(a * 42 + (1 - a) * bb.b) };
			const double d = std::hypot(x - 48.0, y - 36.0);
			matte.at(x, y) = d < 17.5 ? 255 : 0;  // the decision, inside him
			if (d > 26)
				trimap.at(x, y) = kTrimapBoard; // outside the superset
		}
	BoardModel model;
	learnBoard(model, board, 2 + 1); // more visits: the model converges on the board image
	// The model's running mean lands on the board image exactly when it
	// learns the same picture again and again.
	for (int y = 0; y < h; ++y)
		for (int x = 0; x < w; ++x)
			ASSERT_EQ(model.distance(x, y, board.at(x, y)), 0) << x << "," << y;
	Gray8Image expected = matte;
	referenceUnmix(colour, board, trimap, 100, expected);
	BoundaryUnmixing unmixing;
	unmixing.configure(100);
	const Roi roi{ 0, 0, w, h };
	const int changed = unmixing.refine(colour, trimap, model, roi, matte);
	EXPECT_GT(changed, 100); // it did grow the disc
	int differ = 0;
	for (int y = 0; y < h; ++y)
		for (int x = 0; x < w; ++x)
			differ += matte.at(x, y) != expected.at(x, y);
	EXPECT_EQ(differ, 0);
}

TEST(BoundaryUnmixing, GrowsTheEdgeToWhereTheColourPutsTheSilhouette)
{
	StraightEdge e;
	BoardModel model;
	learnBoard(model, e.board, 2);
	BoundaryUnmixing unmixing;
	unmixing.configure(100);
	unmixing.refine(e.colour, e.trimap, model, Roi{ 0, 0, e.kW, e.kH }, e.matte);
	for (int y = 0; y < e.kH; ++y)
		EXPECT_EQ(e.lastLecturerColumn(y), 20) << "row " << y; // the 70 % pixel in, the 30 % one out
}

TEST(BoundaryUnmixing, WithoutALearnedBoardTheBoardNearbyStandsIn)
{
	StraightEdge e;
	BoardModel model;
	const Gray8Image nowhere(e.kW, e.kH, kTrimapUndecided);
	model.learn(e.board, nowhere); // sized, but no pixel learned
	ASSERT_EQ(model.distance(30, 5, e.board.at(30, 5)), -1);
	BoundaryUnmixing unmixing;
	unmixing.configure(100);
	unmixing.refine(e.colour, e.trimap, model, Roi{ 0, 0, e.kW, e.kH }, e.matte);
	for (int y = 0; y < e.kH; ++y)
		EXPECT_EQ(e.lastLecturerColumn(y), 20) << "row " << y;
}

TEST(BoundaryUnmixing, AlikeColoursLeaveTheDecision)
{
	StraightEdge e(25); // |F - B|^2 = 3 * 5^2 = 75 < 100
	BoardModel model;
	learnBoard(model, e.board, 2);
	BoundaryUnmixing unmixing;
	unmixing.configure(100);
	EXPECT_EQ(unmixing.refine(e.colour, e.trimap, model, Roi{ 0, 0, e.kW, e.kH }, e.matte), 0);
	unmixing.configure(0); // off
	StraightEdge clear;
	EXPECT_EQ(unmixing.refine(clear.colour, clear.trimap, model, Roi{ 0, 0, e.kW, e.kH }, clear.matte), 0);
}

TEST(BoundaryUnmixing, NeverShrinksTheLecturerNorLeavesTheSuperset)
{
	StraightEdge e;
	// Column 17, on the decided edge, is lecturer but looks like board: it stays.
	for (int y = 0; y < e.kH; ++y)
		e.colour.at(17, y) = Rgb8{ 20, 20, 20 };
	// Rows 0-3 end the superset at column 18: nothing there grows.
	for (int y = 0; y < 4; ++y)
		for (int x = 18; x < e.kW; ++x)
			e.trimap.at(x, y) = kTrimapBoard;
	BoardModel model;
	learnBoard(model, e.board, 2);
	BoundaryUnmixing unmixing;
	unmixing.configure(100);
	unmixing.refine(e.colour, e.trimap, model, Roi{ 0, 0, e.kW, e.kH }, e.matte);
	for (int y = 0; y < e.kH; ++y) {
		EXPECT_EQ(e.matte.at(17, y), 255);
		if (y < 4)
			EXPECT_EQ(e.lastLecturerColumn(y), 17) << "row " << y;
		else
			EXPECT_GE(e.lastLecturerColumn(y), 18) << "row " << y; // it still grows there
	}
}

// Working only along the edge (issue 28) changes nothing: lecture frames at
// odd and even sizes, the board model learned on part of the image (the
// local board mean elsewhere), the superset leaving some of the board out,
// every kind of ROI (borders, thin, empty), mattes with no edge.
TEST(BoundaryUnmixing, EqualsTheWholeRoiUnmixingBitForBit)
{
	BoundaryUnmixing unmixing;
	test::BoundaryUnmixingWholeRoi reference;
	int changed = 0;
	for (auto [w, h] : { std::pair{ 160, 120 }, std::pair{ 161, 97 }, std::pair{ 33, 17 } }) {
		const test::EdgeScene scene = test::lectureEdgeScene(w, h, 9.0, w > 100 ? 4 : 3);
		BoardModel model;
		Gray8Image learned(w, h, kTrimapUndecided), trimap(w, h, kTrimapUndecided);
		for (int y = 0; y < h; ++y)
			for (int x = 0; x < w; ++x) {
				learned.at(x, y) = x < w * 3 / 5 ? kTrimapBoard : kTrimapUndecided;
				trimap.at(x, y) = y > h * 4 / 5 && x % 7 < 3 ? kTrimapBoard : kTrimapUndecided;
			}
		for (int i = 0; i < 3 * BoardModel::kRowStride; ++i)
			model.learn(scene.room, learned);
		for (int minContrast2 : { 100, 20 })
			for (int matte = 0; matte < 3; ++matte)
				for (const Roi &roi : test::edgeSceneRois(w, h))
				for (KernelPath path : simd_test::kAllPaths) { // the column sums' rows
					// No edge at all: all board, all lecturer.
					Gray8Image out = matte == 0 ? scene.matte : Gray8Image(w, h, matte == 1 ? 0 : 255);
					Gray8Image expected = out;
					unmixing.setKernelPath(path);
					unmixing.configure(minContrast2);
					reference.configure(minContrast2);
					const int n = unmixing.refine(scene.colour, trimap, model, roi, out);
					ASSERT_EQ(n, reference.refine(scene.colour, trimap, model, roi, expected));
					int differ = 0;
					for (int y = 0; y < h; ++y)
						for (int x = 0; x < w; ++x)
							differ += out.at(x, y) != expected.at(x, y);
					ASSERT_EQ(differ, 0) << w << "x" << h << " matte " << matte << " roi " << roi.x0 << ","
							     << roi.y0 << "-" << roi.x1 << "," << roi.y1 << " contrast " << minContrast2
							     << " " << simd_test::pathName(path);
					changed += n;
				}
	}
	EXPECT_GT(changed, 100); // the lecture's edges did grow
	std::printf("boundary unmixing: %d pixels turned, as the whole-ROI unmixing turned them\n", changed);
}
