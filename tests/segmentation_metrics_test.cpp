#include "algo/segmentation_metrics.hpp"
#include "algo/trimap.hpp"
#include "algo/trimap_attribution.hpp"
#include "mask_rect.hpp"

#include <gtest/gtest.h>

using namespace depthkey;
using depthkey::test::maskRect;

TEST(SegmentationMetrics, ShiftedSquareHasKnownIouFnrFpr)
{
	// Truth 4x4 at (2,2); prediction the same square one pixel right:
	// overlap 3x4 = 12, union 20, 4 lost of 16, 4 taken of 84 board pixels.
	Gray8Image truth = maskRect(10, 10, 2, 2, 6, 6);
	Gray8Image pred = maskRect(10, 10, 3, 2, 7, 6);
	SegmentationScorer scorer;
	SegmentationScore s = scorer.score(pred, truth);
	EXPECT_DOUBLE_EQ(s.iou, 12.0 / 20.0);
	EXPECT_DOUBLE_EQ(s.fnr, 4.0 / 16.0);
	EXPECT_DOUBLE_EQ(s.fpr, 4.0 / 84.0);
	// Every boundary pixel is within 1 px of the other's: boundary F = 1.
	EXPECT_DOUBLE_EQ(s.boundaryF, 1.0);
}

TEST(SegmentationMetrics, BoundaryBeyondToleranceScoresZero)
{
	// Left part up to column 9 vs up to column 12: edges 3 px apart.
	SegmentationScorer scorer(2);
	SegmentationScore s = scorer.score(maskRect(20, 10, 0, 0, 13, 10), maskRect(20, 10, 0, 0, 10, 10));
	EXPECT_DOUBLE_EQ(s.boundaryF, 0.0);
	s = scorer.score(maskRect(20, 10, 0, 0, 11, 10), maskRect(20, 10, 0, 0, 10, 10));
	EXPECT_DOUBLE_EQ(s.boundaryF, 1.0);
	EXPECT_DOUBLE_EQ(s.iou, 10.0 / 11.0);
}

TEST(SegmentationMetrics, PartlyMatchedBoundaryHasHandCountedF)
{
	// Truth: columns 0..9, its boundary is column 9 (10 pixels).
	// Prediction: columns 0..9 in rows 0..4, 0..14 in rows 5..9. Its 14
	// boundary pixels: column 9 rows 0..4 (match), row 5 x = 10..14 (x = 10,
	// 11 within 2 px of (9,5)), column 14 rows 6..9 (no): precision 7/14.
	// Truth's: rows 0..4 (match), (9,5) and (9,6) near (10,5) (1, sqrt 2),
	// rows 7..9 not: recall 7/10.
	Gray8Image truth = maskRect(20, 10, 0, 0, 10, 10);
	Gray8Image pred = maskRect(20, 10, 0, 0, 10, 10);
	for (int y = 5; y < 10; ++y)
		for (int x = 10; x < 15; ++x)
			pred.at(x, y) = 255;
	SegmentationScorer scorer(2);
	SegmentationScore s = scorer.score(pred, truth);
	EXPECT_DOUBLE_EQ(s.boundaryPrecision, 0.5);
	EXPECT_DOUBLE_EQ(s.boundaryRecall, 0.7);
	EXPECT_NEAR(s.boundaryF, 2 * 0.5 * 0.7 / 1.2, 1e-12);
	EXPECT_DOUBLE_EQ(s.fnr, 0.0);
	EXPECT_DOUBLE_EQ(s.fpr, 25.0 / 100.0);
}

TEST(SegmentationMetrics, EmptyMasksAndAlphaThreshold)
{
	SegmentationScorer scorer;
	Gray8Image empty(8, 8, 0);
	SegmentationScore s = scorer.score(empty, empty);
	EXPECT_DOUBLE_EQ(s.iou, 1.0);
	EXPECT_DOUBLE_EQ(s.boundaryF, 1.0);
	// An alpha of 127 is board, 128 lecturer.
	Gray8Image alpha(8, 8, 127), truth(8, 8, 128);
	s = scorer.score(alpha, truth);
	EXPECT_DOUBLE_EQ(s.iou, 0.0);
	EXPECT_DOUBLE_EQ(s.fnr, 1.0);
	// Mismatched sizes are a total miss, never a crash.
	s = scorer.score(Gray8Image(4, 4, 255), truth);
	EXPECT_DOUBLE_EQ(s.fnr, 1.0);
}

TEST(SegmentationMetrics, AverageWeighsFramesEqually)
{
	ScoreAverage avg;
	SegmentationScore a, b;
	a.iou = 1.0;
	b.iou = 0.5;
	avg.add(a);
	avg.add(b);
	EXPECT_EQ(avg.frames(), 2);
	EXPECT_DOUBLE_EQ(avg.mean().iou, 0.75);
}

TEST(TrimapAttribution, WrongPixelsBySeedAndBandAndTheBoundOfTheSeeds)
{
	// Four pixels: surely lecturer, band, band, surely board.
	Gray8Image trimap(4, 1), truth(4, 1), alpha(4, 1);
	const uint8_t t[] = { kTrimapLecturer, kTrimapUndecided, kTrimapUndecided, kTrimapBoard };
	const uint8_t is[] = { 255, 255, 0, 0 };
	const uint8_t said[] = { 255, 0, 200, 255 }; // band: one lost, one taken; the board seed wrong
	for (int x = 0; x < 4; ++x) {
		trimap.at(x, 0) = t[x];
		truth.at(x, 0) = is[x];
		alpha.at(x, 0) = said[x];
	}
	SegmentationScorer scorer(2);
	TrimapAttribution a;
	a.add(alpha, truth, trimap, scorer);
	using R = TrimapAttribution::Region;
	EXPECT_EQ(a.pixels(R::SurelyLecturer), 1u);
	EXPECT_EQ(a.wrong(R::SurelyLecturer), 0u);
	EXPECT_EQ(a.pixels(R::Band), 2u);
	EXPECT_EQ(a.wrong(R::Band), 2u);
	EXPECT_EQ(a.bandTaken(), 1u);
	EXPECT_EQ(a.wrong(R::SurelyBoard), 1u);
	// Band decided right: lecturer, lecturer, board, lecturer -> IoU 2 / 3.
	EXPECT_NEAR(a.bound().iou, 2.0 / 3.0, 1e-9);
	a.add(alpha, truth, Gray8Image(3, 1), scorer); // a trimap of another size: ignored
	EXPECT_EQ(a.pixels(R::Band), 2u);
}
