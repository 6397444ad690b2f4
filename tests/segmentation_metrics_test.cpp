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

namespace {

// The scorer as first written (pixel by pixel through at()), kept as the
// reference the row-wise scorer must agree with exactly.
SegmentationScore referenceScore(const Gray8Image &pred, const Gray8Image &truth, int tolerance)
{
	const int w = truth.width(), h = truth.height();
	auto in = [](const Gray8Image &m, int x, int y) { return m.at(x, y) >= 128; };
	auto edges = [&](const Gray8Image &m) {
		Gray8Image e(w, h, 0);
		for (int y = 0; y < h; ++y)
			for (int x = 0; x < w; ++x)
				e.at(x, y) = in(m, x, y) && ((x > 0 && !in(m, x - 1, y)) || (x + 1 < w && !in(m, x + 1, y)) ||
							     (y > 0 && !in(m, x, y - 1)) || (y + 1 < h && !in(m, x, y + 1)));
		return e;
	};
	auto matched = [&](const Gray8Image &from, const Gray8Image &to) {
		long hits = 0, total = 0;
		for (int y = 0; y < h; ++y)
			for (int x = 0; x < w; ++x) {
				if (!from.at(x, y))
					continue;
				total++;
				bool hit = false;
				for (int dy = -tolerance; dy <= tolerance && !hit; ++dy)
					for (int dx = -tolerance; dx <= tolerance && !hit; ++dx)
						hit = dx * dx + dy * dy <= tolerance * tolerance && x + dx >= 0 && y + dy >= 0 &&
						      x + dx < w && y + dy < h && to.at(x + dx, y + dy);
				hits += hit;
			}
		return std::pair<long, long>{ hits, total };
	};
	long both = 0, either = 0, t = 0, lost = 0, taken = 0;
	for (int y = 0; y < h; ++y)
		for (int x = 0; x < w; ++x) {
			bool p = in(pred, x, y), q = in(truth, x, y);
			both += p && q;
			either += p || q;
			t += q;
			lost += q && !p;
			taken += p && !q;
		}
	SegmentationScore s;
	const long board = long(w) * h - t;
	s.iou = either ? double(both) / either : 1.0;
	s.fnr = t ? double(lost) / t : 0.0;
	s.fpr = board ? double(taken) / board : 0.0;
	auto [pHits, pTotal] = matched(edges(pred), edges(truth));
	auto [tHits, tTotal] = matched(edges(truth), edges(pred));
	if (pTotal == 0 && tTotal == 0) {
		s.boundaryPrecision = s.boundaryRecall = s.boundaryF = 1.0;
		return s;
	}
	s.boundaryPrecision = pTotal ? double(pHits) / pTotal : 0.0;
	s.boundaryRecall = tTotal ? double(tHits) / tTotal : 0.0;
	const double sum = s.boundaryPrecision + s.boundaryRecall;
	s.boundaryF = sum > 0 ? 2 * s.boundaryPrecision * s.boundaryRecall / sum : 0.0;
	return s;
}

// Blobs and speckle around the threshold: values near 128 on both sides.
Gray8Image blobs(int w, int h, uint32_t seed)
{
	Gray8Image m(w, h, 0);
	for (int y = 0; y < h; ++y)
		for (int x = 0; x < w; ++x) {
			seed = seed * 1664525u + 1013904223u;
			const double cx = w * 0.5 + (seed % 7), cy = h * 0.4;
			const bool inBlob = (x - cx) * (x - cx) / (w * w * 0.06 + 1) + (y - cy) * (y - cy) / (h * h * 0.1 + 1) < 1;
			const uint32_t r = seed >> 24;
			m.at(x, y) = r < 20 ? uint8_t(127 + (r & 1)) : (inBlob != (r < 40) ? 255 : uint8_t(r & 127));
		}
	return m;
}

} // namespace

TEST(SegmentationMetrics, RowWiseScorerAgreesExactlyWithThePixelByPixelReference)
{
	const int sizes[][2] = { { 1, 1 }, { 1, 9 }, { 9, 1 }, { 2, 2 }, { 3, 5 }, { 17, 13 }, { 64, 48 }, { 160, 120 } };
	for (int tolerance : { 0, 1, 2, 3 }) {
		SegmentationScorer scorer(tolerance);
		for (const auto &size : sizes)
			for (uint32_t seed = 1; seed <= 6; ++seed) {
				const Gray8Image pred = blobs(size[0], size[1], seed), truth = blobs(size[0], size[1], seed + 100);
				const SegmentationScore got = scorer.score(pred, truth);
				const SegmentationScore want = referenceScore(pred, truth, tolerance);
				SCOPED_TRACE(::testing::Message() << size[0] << "x" << size[1] << " seed " << seed << " tol "
								  << tolerance);
				EXPECT_EQ(got.iou, want.iou);
				EXPECT_EQ(got.fnr, want.fnr);
				EXPECT_EQ(got.fpr, want.fpr);
				EXPECT_EQ(got.boundaryPrecision, want.boundaryPrecision);
				EXPECT_EQ(got.boundaryRecall, want.boundaryRecall);
				EXPECT_EQ(got.boundaryF, want.boundaryF);
			}
	}
}
