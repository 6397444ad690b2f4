// The evidence fusion kernel against the divisions it replaced (equal, for
// every input and a spread of weights), against a double reference
// (tolerance: 2 confidence units, one per truncating division), and the
// direction of each term: depth, the board model and the previous frame move
// the decision the way they should.
#include <gtest/gtest.h>

#include "algo/exact_divisor.hpp"
#include "algo/fused_evidence.hpp"
#include "tests/simd_paths.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

using namespace depthkey;

namespace {

// Depth evidence values (DepthSeeder::depthEvidence): clean depth on his
// surface, clean depth on the board, and a mixed pixel at his silhouette
// leaning his way.
constexpr int kDepthSaysLecturer = 254, kDepthSaysBoard = 1, kDepthAtTheEdge = 176;

double fuseReference(const DecisionSettings &s, int siox, int depthEvidence, int boardDistance, int previousAlpha,
		     int change, bool movedLately)
{
	double sum = siox - 128.0;
	if (boardDistance >= 0 && boardDistance < s.boardMatch)
		sum -= s.boardWeight * double(s.boardMatch - boardDistance) / s.boardMatch;
	else if (boardDistance > 2 * s.boardMatch)
		sum += s.boardWeight * std::min(boardDistance - 2.0 * s.boardMatch, double(s.boardMatch)) /
		       (2.0 * s.boardMatch);
	const double colourAndBoard = sum;
	if (previousAlpha >= 0 && change < s.stillColour)
		sum += s.temporalWeight * (previousAlpha - 128.0) / 128.0 * (s.stillColour - change) / s.stillColour;
	sum = std::clamp(sum, -127.0, 127.0); // the colour camera's say, capped
	const double depth = s.depthWeight * (depthEvidence - s.depthPivot) / 64.0;
	// Colour and the board model sure of him where the colour moved, or
	// moved lately and he was there in the last frame: depth's board verdict
	// held (a hand writing on the board, and holding still against it).
	const bool moved = previousAlpha >= 0 && change >= s.stillColour;
	const bool held = moved || (movedLately && previousAlpha >= 128);
	sum += colourAndBoard >= FusedEvidence::kSureLecturerColour && held
		       ? std::max(depth, -double(FusedEvidence::kContactDepthFloor))
		       : depth;
	return std::clamp(sum + 128.0, 1.0, 255.0);
}

// The kernel as it was before issue 28, three integer divisions a pixel:
// the tables and the multiply must give exactly this.
int fuseWithDivisions(const DecisionSettings &s, int siox, int depthEvidence, int boardDistance, int previousAlpha,
		      int colourChange, bool movedLately)
{
	int sum = siox - kConfidenceLecturer;
	if (boardDistance >= 0 && boardDistance < s.boardMatch)
		sum -= s.boardWeight * (s.boardMatch - boardDistance) / s.boardMatch;
	else if (boardDistance > 2 * s.boardMatch)
		sum += s.boardWeight * std::min(boardDistance - 2 * s.boardMatch, s.boardMatch) / (2 * s.boardMatch);
	const int colourAndBoard = sum;
	if (previousAlpha >= 0 && colourChange < s.stillColour)
		sum += s.temporalWeight * (previousAlpha - 128) * (s.stillColour - colourChange) / (128 * s.stillColour);
	sum = std::clamp(sum, 1 - int(kConfidenceLecturer), 255 - int(kConfidenceLecturer));
	const int depth = (s.depthWeight * (depthEvidence - s.depthPivot)) >> 6;
	const bool moved = previousAlpha >= 0 && colourChange >= s.stillColour;
	const bool held = moved || (movedLately && previousAlpha >= 128);
	sum += colourAndBoard >= FusedEvidence::kSureLecturerColour && held
		       ? std::max(depth, -FusedEvidence::kContactDepthFloor)
		       : depth;
	return std::clamp(sum + int(kConfidenceLecturer), 1, 255);
}

FusedEvidence configured(const DecisionSettings &s)
{
	FusedEvidence f;
	f.configure(s);
	return f;
}

} // namespace

TEST(ExactDivisor, EqualsTheDivisionForEveryNumeratorItIsUsedWith)
{
	// The temporal term's divisors 128 * (1..255), every numerator the term
	// can have (|n| <= 255 * 128 * 255), and divisors at the limits.
	ExactDivisor divisor;
	for (int still = 1; still <= 255; ++still) {
		const int d = 128 * still;
		divisor.set(uint32_t(d));
		for (int n = -255 * 128 * 255; n <= 255 * 128 * 255; n += 1 + still * 97)
			ASSERT_EQ(divisor.truncate(n), n / d) << n << " / " << d;
		for (int n : { 0, 1, d - 1, d, d + 1, -d + 1, -d, -d - 1 })
			ASSERT_EQ(divisor.truncate(n), n / d) << n << " / " << d;
	}
	for (uint32_t d : { 1u, 2u, 3u, 7u, 641u, 65535u, 65537u, (1u << 31) - 1 }) {
		divisor.set(d);
		for (uint32_t n : { 0u, 1u, d - 1, d, (1u << 31) - 1, (1u << 31) - 2, 2147483646u / d * d })
			ASSERT_EQ(divisor.floor(n), n / d) << n << " / " << d;
	}
}

TEST(FusedEvidence, TablesEqualTheDivisionsTheyReplaced)
{
	// Every input a frame can give, under the defaults and weights at
	// their limits (boardMatch and stillColour 1 and 255).
	std::vector<DecisionSettings> settings(5);
	settings[1].boardMatch = 1;
	settings[1].stillColour = 1;
	settings[2].boardMatch = 255;
	settings[2].stillColour = 255;
	settings[2].boardWeight = settings[2].temporalWeight = settings[2].depthWeight = 255;
	settings[3].boardWeight = settings[3].temporalWeight = settings[3].depthWeight = 0;
	settings[4].boardMatch = 37;
	settings[4].stillColour = 7;
	settings[4].depthPivot = 1;
	settings[4].temporalWeight = 201;
	for (const DecisionSettings &s : settings) {
		const FusedEvidence f = configured(s);
		// Distances and changes: all the small ones, both sides of each
		// threshold, and a stride beyond.
		std::vector<int> boards, changes;
		const int m = s.boardMatch, still = s.stillColour;
		for (int d = -1; d <= 60; ++d)
			boards.push_back(d);
		for (int d : { m - 1, m, m + 1, 2 * m - 1, 2 * m, 2 * m + 1, 3 * m - 1, 3 * m, 3 * m + 1, 765, 800 })
			boards.push_back(d);
		for (int d = 61; d < 765; d += 23)
			boards.push_back(d);
		for (int c = 0; c <= 40; ++c)
			changes.push_back(c);
		for (int c : { still - 1, still, still + 1, 765 })
			changes.push_back(c);
		for (int c = 41; c < 765; c += 17)
			changes.push_back(c);
		size_t compared = 0, differ = 0;
		// Colour and depth at their ends and around neutral: they only
		// shift the sum into and past the clamps.
		for (int siox : { 1, 2, 40, 100, 127, 128, 129, 160, 220, 254, 255 })
			for (int depth : { 0, 1, 60, s.depthPivot - 1, s.depthPivot, s.depthPivot + 1, 200, 254, 255 })
				for (int board : boards)
					for (int previous = -1; previous <= 255; previous += previous < 2 ? 1 : 51)
						for (int change : changes)
							for (bool lately : { false, true }) {
								// Counted, not asserted one by one (millions).
								const int fused = f.fuse(siox, depth, board, previous, change, lately);
								const int divided =
									fuseWithDivisions(s, siox, depth, board, previous, change, lately);
								if (fused != divided && differ++ == 0)
									ADD_FAILURE() << "siox " << siox << " depth " << depth << " board "
										      << board << " previous " << previous << " change "
										      << change << " lately " << lately << ": " << fused
										      << " against " << divided;
								++compared;
							}
		EXPECT_EQ(differ, 0u) << "of " << compared;
		EXPECT_GT(compared, 100000u);
	}
}

TEST(FusedEvidence, FixedPointMatchesTheDoubleReferenceWithinTwoUnits)
{
	const DecisionSettings s;
	const FusedEvidence f = configured(s);
	std::map<int, int> histogram;
	int worst = 0;
	for (int siox = 1; siox <= 255; siox += 7)
		for (int depth = 0; depth <= 255; depth += 11)
			for (int board = -1; board < 120; board += 9)
				for (int previous = -1; previous <= 255; previous += 64)
					for (int change = 0; change < 40; change += 13)
						for (bool lately : { false, true }) {
							const int fixed = f.fuse(siox, depth, board, previous, change, lately);
							const double ref = fuseReference(s, siox, depth, board, previous, change, lately);
							const int error = int(std::ceil(std::abs(fixed - ref) - 1e-9));
							histogram[error]++;
							worst = std::max(worst, error);
						}
	std::printf("fused confidence, fixed vs double, |error| histogram:");
	for (auto [e, n] : histogram)
		std::printf(" %d:%d", e, n);
	std::printf("\n");
	EXPECT_LE(worst, 2);
}

TEST(FusedEvidence, EachTermPullsItsWay)
{
	const DecisionSettings s;
	const FusedEvidence f = configured(s);
	const int neutralColour = 128, noModel = -1, noPrevious = -1;
	// Colour ambiguous: clean depth decides.
	EXPECT_GE(f.fuse(neutralColour, kDepthSaysLecturer, noModel, noPrevious, 0),
		  kConfidenceLecturer);
	EXPECT_LT(f.fuse(neutralColour, kDepthSaysBoard, noModel, noPrevious, 0), kConfidenceLecturer);
	// Clean depth outweighs a clear colour either way (a dark sleeve on
	// the dark board; a white shirt's colour on the board beside him).
	EXPECT_GE(f.fuse(20, kDepthSaysLecturer, noModel, noPrevious, 0), kConfidenceLecturer);
	EXPECT_LT(f.fuse(236, kDepthSaysBoard, noModel, noPrevious, 0), kConfidenceLecturer);
	// Colour says lecturer (white chalk like a white shirt), depth at its
	// edge: the board model's match at this pixel says board.
	EXPECT_GE(f.fuse(200, kDepthAtTheEdge, noModel, noPrevious, 0), kConfidenceLecturer);
	EXPECT_LT(f.fuse(200, kDepthAtTheEdge, 2, noPrevious, 0), kConfidenceLecturer);
	// Colour says board (a dark vest on the dark board) but the pixel is
	// far from how the board looks there, and in range: lecturer.
	EXPECT_GE(f.fuse(60, kDepthAtTheEdge, 90, noPrevious, 0), kConfidenceLecturer);
	// The previous frame counts only where the colour did not change.
	const int still = f.fuse(neutralColour, s.depthPivot, noModel, 255, 0);
	const int moved = f.fuse(neutralColour, s.depthPivot, noModel, 255, s.stillColour);
	EXPECT_GT(still, moved);
	EXPECT_EQ(moved, f.fuse(neutralColour, s.depthPivot, noModel, noPrevious, 0));
	// A hand writing on the board (issue 29 section 6): depth says board as
	// surely as on the board; skin clearly his by colour, far from how the
	// board looks here, and moving keeps him, even after a frame that lost
	// him. Still (the desk beside him, his colours too), or where the board
	// looks like that, depth decides: board.
	const int lost = 0;
	EXPECT_GE(f.fuse(250, kDepthSaysBoard, 90, lost, s.stillColour), kConfidenceLecturer);
	EXPECT_LT(f.fuse(250, kDepthSaysBoard, 90, lost, 0), kConfidenceLecturer);
	EXPECT_LT(f.fuse(250, kDepthSaysBoard, 90, noPrevious, 0), kConfidenceLecturer);
	EXPECT_LT(f.fuse(250, kDepthSaysBoard, 2, lost, s.stillColour), kConfidenceLecturer);
	// Holding still against the board, moved lately: kept where he was in
	// the last frame; not where the last frame lost him, nor where nothing
	// moved lately (the desk).
	const int his = 255;
	EXPECT_GE(f.fuse(250, kDepthSaysBoard, 90, his, 0, true), kConfidenceLecturer);
	EXPECT_LT(f.fuse(250, kDepthSaysBoard, 90, lost, 0, true), kConfidenceLecturer);
	EXPECT_LT(f.fuse(250, kDepthSaysBoard, 90, his, 0, false), kConfidenceLecturer);
	EXPECT_LT(f.fuse(250, kDepthSaysBoard, 2, his, 0, true), kConfidenceLecturer);
}

// The hold through still moments, through confidences() frame by frame: a
// pixel sure his by colour, on the board by depth, his in the last frame,
// whose colour moved once and then held still, is kept for kHoldFrames
// frames counted from the move (the moving frame included), then depth
// decides again; a pixel that never moved is never held. Nor is one where
// depth saw him in front of the board within kHoldFrames: he stood there and
// walked off (pixel 2: at 1920x1080 the floor his legs left, as light as his
// shirt, was held as a ghost for a second).
TEST(FusedEvidence, AStillHandIsHeldForAWhileAfterItMoved)
{
	const int w = 4, h = 1;
	const Rgb8 skin{ 200, 40, 40 }, board{ 40, 80, 60 }, elsewhere{ 90, 200, 200 };
	RgbImage colour(w, h, skin), moved(w, h, skin), still(w, h, skin);
	moved.at(0, 0) = elsewhere; // pixels 0 and 2 moved in the first frame; pixel 1 never
	moved.at(2, 0) = elsewhere;
	Gray8Image depth(w, h, uint8_t(kDepthSaysBoard)), previousAlpha(w, h, 255), trimap(w, h, kTrimapBoard);
	Gray8Image depthLeaving = depth; // in the first frame, depth saw him in front at pixel 2
	depthLeaving.at(2, 0) = uint8_t(kDepthSaysLecturer);
	BoardModel model;
	RgbImage boardColour(w, h, board);
	for (int i = 0; i < 3 * BoardModel::kRowStride; ++i)
		model.learn(boardColour, trimap);
	QuantisedLab lab;
	SioxClassifier classifier(lab);
	WeightedLab lecturer[] = { { lab[quantiseColour(skin)], 10 } };
	WeightedLab boardPoints[] = { { lab[quantiseColour(board)], 10 } };
	classifier.lecturer().build(lecturer, 1);
	classifier.board().build(boardPoints, 1);
	classifier.signaturesChanged();
	FusedEvidence f = configured(DecisionSettings());
	const Roi roi{ 0, 0, w, h };
	for (int frame = 0; frame < FusedEvidence::kHoldFrames + 3; ++frame) {
		f.bind(colour, frame == 0 ? depthLeaving : depth, classifier, model, &previousAlpha,
		       frame == 0 ? &moved : &still, roi);
		uint8_t row[w];
		f.confidences(0, 0, w, row);
		const bool held = frame < FusedEvidence::kHoldFrames;
		EXPECT_EQ(row[0] >= kConfidenceLecturer, held) << "frame " << frame << ": " << int(row[0]);
		EXPECT_LT(row[1], kConfidenceLecturer) << "frame " << frame << ": never moved, never held";
		if (frame > 0) {
			EXPECT_LT(row[2], kConfidenceLecturer) << "frame " << frame << ": depth saw him in front lately";
		}
	}
}

// confidences() splits a row at the previous frame's ROI (issue 28) instead
// of testing it at every pixel: each pixel must still get exactly fuse() of
// its own terms, with the previous frame only inside that ROI, wherever the
// ROI starts and ends against the row's span, on every kernel path (the
// board distance and colour change rows, algo/evidence_terms_rows.hpp).
TEST(FusedEvidence, ARowEqualsFuseOfEachPixel)
{
	const int w = 48, h = 6;
	RgbImage colour(w, h), previousColour(w, h);
	Gray8Image depth(w, h), previousAlpha(w, h), trimap(w, h, kTrimapBoard);
	for (int y = 0; y < h; ++y)
		for (int x = 0; x < w; ++x) {
			const int v = (x * 37 + y * 11) & 255;
			colour.at(x, y) = { uint8_t(v), uint8_t(255 - v), uint8_t((v * 3) & 255) };
			// Some pixels still (the temporal term counts), some changed.
			previousColour.at(x, y) = x % 3 ? colour.at(x, y) : Rgb8{ uint8_t(v ^ 40), 9, 9 };
			depth.at(x, y) = uint8_t((x * 53 + y) & 255);
			previousAlpha.at(x, y) = uint8_t(x % 2 ? 255 : (x * 29) & 255);
		}
	// A board model learned on half the rows' pixels (the rest: none).
	RgbImage boardColour(w, h, Rgb8{ 40, 80, 60 });
	for (int x = 0; x < w / 2; ++x)
		for (int y = 0; y < h; ++y)
			trimap.at(x, y) = kTrimapUndecided;
	BoardModel board;
	for (int i = 0; i < 3 * BoardModel::kRowStride; ++i)
		board.learn(boardColour, trimap);
	QuantisedLab lab;
	SioxClassifier classifier(lab);
	WeightedLab lecturer[] = { { lab[quantiseColour({ 200, 40, 40 })], 10 } };
	WeightedLab boardPoints[] = { { lab[quantiseColour({ 40, 80, 60 })], 10 } };
	classifier.lecturer().build(lecturer, 1);
	classifier.board().build(boardPoints, 1);
	classifier.signaturesChanged();
	const FusedEvidence reference = configured(DecisionSettings());
	FusedEvidence f = configured(DecisionSettings());
	size_t compared = 0;
	for (KernelPath path : simd_test::kAllPaths)
	for (int px0 : { 0, 5, 20, 47 })
		for (int px1 : { 6, 21, 48 }) {
			if (px1 <= px0)
				continue;
			const Roi previousRoi{ px0, 1, px1, h - 1 };
			f.setKernelPath(path);
			f.bind(colour, depth, classifier, board, &previousAlpha, &previousColour, previousRoi);
			for (int y = 0; y < h; ++y)
				for (auto [x0, x1] : { std::pair{ 0, w }, std::pair{ 3, 19 }, std::pair{ 21, 40 }, std::pair{ 30, 31 } }) {
					uint8_t row[w];
					f.confidences(y, x0, x1, row);
					for (int x = x0; x < x1; ++x) {
						const Rgb8 c = colour.at(x, y);
						const bool inPrevious = y >= previousRoi.y0 && y < previousRoi.y1 &&
									x >= previousRoi.x0 && x < previousRoi.x1;
						const Rgb8 p = previousColour.at(x, y);
						const int change = std::abs(c.r - p.r) + std::abs(c.g - p.g) + std::abs(c.b - p.b);
						const int expected = reference.fuse(
							classifier.confidence(quantiseColour(c)), depth.at(x, y),
							board.distance(x, y, c), inPrevious ? previousAlpha.at(x, y) : -1,
							inPrevious ? change : 0);
						ASSERT_EQ(row[x - x0], expected) << simd_test::pathName(path) << " x " << x << " y " << y << " roi " << px0
										 << ".." << px1;
						++compared;
					}
				}
		}
	EXPECT_GT(compared, 1000u);
}
