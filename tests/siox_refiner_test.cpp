// SioxRefiner (algo/siox_refiner.hpp) on small synthetic trimaps with a fake
// BandEvidence that hands out a confidence map, one rule per test: only band
// pixels are asked about and changed, seeds are never contradicted, band
// regions touching the core (or the border, when the lecturer goes on beyond
// it) are kept, specks are dropped and large free regions kept, enclosed
// holes are filled except where the evidence says clearly board, and the
// soft alpha stays on the side of the decision; every kernel path of the
// band scan gives the same alpha.
#include "algo/siox_refiner.hpp"
#include "tests/simd_paths.hpp"

#include <gtest/gtest.h>

#include <random>

using namespace depthkey;

namespace {

// 12288 pixels: a free region is kept from kFreeComponentMinPx (400) on.
constexpr int kW = 128, kH = 96;
constexpr uint8_t kLecturerSays = 200, kBoardSays = 100, kClearlyBoardSays = 10;

// The confidence map as evidence; counts what it was asked for.
class MapEvidence final : public BandEvidence
{
public:
	explicit MapEvidence(const Gray8Image &map) : map_(map) {}
	void confidences(int y, int x0, int x1, uint8_t *out) override
	{
		for (int x = x0; x < x1; ++x) {
			*out++ = map_.at(x, y);
			asked.push_back({ x, y });
		}
	}
	struct Pixel {
		int x, y;
	};
	std::vector<Pixel> asked;

private:
	const Gray8Image &map_;
};

void fill(Gray8Image &image, int x0, int y0, int x1, int y1, uint8_t value)
{
	for (int y = y0; y < y1; ++y)
		for (int x = x0; x < x1; ++x)
			image.at(x, y) = value;
}

// Board seeds around a band x[4,124) y[4,92) around a core x[56,72) y[40,56);
// the evidence says clearly board everywhere until a test says otherwise.
struct Scene {
	Gray8Image trimap{ kW, kH, kTrimapBoard };
	Gray8Image evidence{ kW, kH, kClearlyBoardSays };
	Scene()
	{
		fill(trimap, 4, 4, 124, 92, kTrimapUndecided);
		fill(trimap, 56, 40, 72, 56, kTrimapLecturer);
	}
};

// Hard decisions (no smoothing, no soft alpha) unless a test asks for them.
Gray8Image refine(const Gray8Image &trimap, const Gray8Image &evidence, int smoothing = 0, bool softAlpha = false,
		  bool beyondBorder = false, Roi roi = { 0, 0, kW, kH })
{
	SioxRefiner refiner;
	SioxSettings settings;
	settings.smoothing = smoothing;
	settings.softAlpha = softAlpha;
	refiner.configure(settings);
	refiner.setLecturerBeyondBorder(beyondBorder);
	RgbImage colour(trimap.width(), trimap.height());
	MapEvidence fake(evidence);
	Gray8Image alpha;
	refiner.refine(colour, trimap, roi, fake, alpha);
	return alpha;
}

size_t countEqual(const Gray8Image &image, int x0, int y0, int x1, int y1, uint8_t value)
{
	size_t n = 0;
	for (int y = y0; y < y1; ++y)
		for (int x = x0; x < x1; ++x)
			n += image.at(x, y) == value;
	return n;
}

} // namespace

TEST(SioxRefiner, OnlyBandPixelsAreAskedAndSeedsAreNeverContradicted)
{
	// Random labels (the graded band values too) and random confidences,
	// every setting: whatever the decision, a seed keeps its label and only
	// the band is asked about.
	std::mt19937 random(16);
	const uint8_t labels[] = { kTrimapBoard, kTrimapUndecided, kTrimapLecturer, kTrimapInRange, kTrimapSubset };
	for (int round = 0; round < 24; ++round) {
		Gray8Image trimap(kW, kH), evidence(kW, kH);
		for (size_t i = 0; i < trimap.size(); ++i) {
			trimap.data()[i] = labels[random() % 5];
			evidence.data()[i] = uint8_t(1 + random() % 255);
		}
		SioxRefiner refiner;
		SioxSettings settings;
		settings.smoothing = round % 4;
		settings.softAlpha = round % 2;
		refiner.configure(settings);
		refiner.setLecturerBeyondBorder(round % 3 == 0);
		RgbImage colour(kW, kH);
		MapEvidence fake(evidence);
		Gray8Image alpha;
		refiner.refine(colour, trimap, { 0, 0, kW, kH }, fake, alpha);

		size_t band = 0;
		for (int y = 0; y < kH; ++y)
			for (int x = 0; x < kW; ++x) {
				const uint8_t t = trimap.at(x, y);
				if (t == kTrimapLecturer)
					ASSERT_EQ(alpha.at(x, y), 255) << x << "," << y << " round " << round;
				else if (t == kTrimapBoard)
					ASSERT_EQ(alpha.at(x, y), 0) << x << "," << y << " round " << round;
				else
					++band;
			}
		EXPECT_EQ(refiner.bandPixels(), band);
		ASSERT_EQ(fake.asked.size(), band) << "each band pixel asked once";
		for (const MapEvidence::Pixel &p : fake.asked) {
			const uint8_t t = trimap.at(p.x, p.y);
			ASSERT_TRUE(t != kTrimapBoard && t != kTrimapLecturer) << p.x << "," << p.y;
		}
	}
}

TEST(SioxRefiner, OutsideTheRoiTheAlphaIsZero)
{
	Scene s;
	fill(s.evidence, 4, 4, 124, 92, kLecturerSays);
	// The ROI holds every non-board pixel with one to spare.
	Gray8Image alpha = refine(s.trimap, s.evidence, 0, false, false, { 3, 3, 125, 93 });
	ASSERT_EQ(alpha.width(), kW);
	ASSERT_EQ(alpha.height(), kH);
	EXPECT_EQ(countEqual(alpha, 4, 4, 124, 92, 255), size_t(120 * 88)) << "the band is all lecturer";
	EXPECT_EQ(countEqual(alpha, 0, 0, kW, kH, 0), size_t(kW * kH - 120 * 88));
}

TEST(SioxRefiner, ARegionTouchingTheCoreIsKeptASpeckIsDropped)
{
	Scene s;
	fill(s.evidence, 52, 40, 56, 56, kLecturerSays); // 64 px against the core's left side
	fill(s.evidence, 8, 60, 18, 70, kLecturerSays);  // 100 px alone in the band
	Gray8Image alpha = refine(s.trimap, s.evidence);
	EXPECT_EQ(countEqual(alpha, 52, 40, 56, 56, 255), 64u);
	EXPECT_EQ(countEqual(alpha, 8, 60, 18, 70, 0), 100u);
	// Nothing else of the band became lecturer.
	EXPECT_EQ(countEqual(alpha, 0, 0, kW, kH, 255), size_t(16 * 16 + 64));
}

TEST(SioxRefiner, ALargeRegionCutOffFromTheCoreIsKept)
{
	Scene s;
	fill(s.evidence, 8, 8, 38, 24, kLecturerSays); // 480 px: an arm cut off by board-coloured clothes
	fill(s.evidence, 8, 60, 27, 81, kLecturerSays); // 399 px: one short of kFreeComponentMinPx
	Gray8Image alpha = refine(s.trimap, s.evidence);
	EXPECT_EQ(countEqual(alpha, 8, 8, 38, 24, 255), 480u);
	EXPECT_EQ(countEqual(alpha, 8, 60, 27, 81, 0), 399u);
}

TEST(SioxRefiner, ARegionAtTheBorderIsKeptOnlyWhenTheLecturerGoesOnBeyondIt)
{
	Gray8Image trimap(kW, kH, kTrimapBoard), evidence(kW, kH, kClearlyBoardSays);
	fill(trimap, 0, 0, 20, kH, kTrimapUndecided);
	fill(evidence, 0, 10, 10, 20, kLecturerSays); // 100 px at the left border, no seed
	EXPECT_EQ(countEqual(refine(trimap, evidence), 0, 10, 10, 20, 0), 100u);
	EXPECT_EQ(countEqual(refine(trimap, evidence, 0, false, true), 0, 10, 10, 20, 255), 100u);
}

TEST(SioxRefiner, AnEnclosedHoleIsFilledUnlessTheEvidenceSaysClearlyBoard)
{
	Scene s;
	// A lecturer ring of 500 px (kept for its size) around a 20x20 hole.
	fill(s.evidence, 80, 60, 110, 90, kLecturerSays);
	fill(s.evidence, 85, 65, 105, 85, kBoardSays);
	Gray8Image alpha = refine(s.trimap, s.evidence);
	EXPECT_EQ(countEqual(alpha, 80, 60, 110, 90, 255), 900u) << "board, but not clearly: filled";

	fill(s.evidence, 85, 65, 105, 85, kClearlyBoardSays);
	fill(s.evidence, 90, 70, 100, 80, kBoardSays); // a patch inside: still enclosed
	alpha = refine(s.trimap, s.evidence);
	EXPECT_EQ(countEqual(alpha, 80, 60, 110, 90, 255), 500u + 100u)
		<< "the clearly-board pixels stay board, the rest of the hole is filled";
	EXPECT_EQ(countEqual(alpha, 90, 70, 100, 80, 255), 100u);
}

TEST(SioxRefiner, AHoleThatReachesABoardSeedStaysBoard)
{
	Scene s;
	fill(s.evidence, 80, 60, 110, 90, kLecturerSays);
	fill(s.evidence, 85, 65, 105, 85, kBoardSays);
	s.trimap.at(95, 75) = kTrimapBoard; // the board seen between arm and body
	Gray8Image alpha = refine(s.trimap, s.evidence);
	EXPECT_EQ(countEqual(alpha, 85, 65, 105, 85, 0), 400u);
	EXPECT_EQ(countEqual(alpha, 80, 60, 110, 90, 255), 500u);
}

TEST(SioxRefiner, SmoothingRemovesAOnePixelFlip)
{
	Scene s;
	fill(s.evidence, 52, 40, 56, 56, kLecturerSays);
	s.evidence.at(54, 30) = kLecturerSays; // one pixel in a board area of the band
	s.evidence.at(53, 48) = kClearlyBoardSays; // one pixel in a lecturer area (clearly board: no hole filling)
	Gray8Image hard = refine(s.trimap, s.evidence);
	EXPECT_EQ(hard.at(53, 48), 0) << "without smoothing the flip is decided as it is";
	Gray8Image smooth = refine(s.trimap, s.evidence, 1);
	EXPECT_EQ(smooth.at(54, 30), 0);
	EXPECT_EQ(smooth.at(53, 48), 255);
	// Inside the region away from its outer corners, all lecturer still.
	EXPECT_EQ(countEqual(smooth, 53, 41, 56, 55, 255), 42u);
}

TEST(SioxRefiner, TheSoftAlphaStaysOnTheSideOfTheDecision)
{
	Scene s;
	std::mt19937 random(7);
	for (size_t i = 0; i < s.evidence.size(); ++i)
		s.evidence.data()[i] = uint8_t(1 + random() % 127); // board, not clearly so for most
	for (int y = 30; y < 66; ++y)
		for (int x = 40; x < 88; ++x)
			s.evidence.at(x, y) = uint8_t(128 + random() % 128); // lecturer around the core
	for (int smoothing : { 0, 1, 2 }) {
		Gray8Image hard = refine(s.trimap, s.evidence, smoothing, false);
		Gray8Image soft = refine(s.trimap, s.evidence, smoothing, true);
		size_t fractional = 0;
		for (int y = 0; y < kH; ++y)
			for (int x = 0; x < kW; ++x) {
				const uint8_t a = soft.at(x, y), h = hard.at(x, y);
				ASSERT_TRUE(h == 0 || h == 255);
				ASSERT_EQ(a >= kConfidenceLecturer, h == 255) << x << "," << y << " smoothing " << smoothing;
				if (a != h) {
					// Only band pixels on the boundary take their confidence.
					ASSERT_EQ(s.trimap.at(x, y), kTrimapUndecided);
					const uint8_t c = s.evidence.at(x, y);
					ASSERT_EQ(a, h ? std::max(c, kConfidenceLecturer) : std::min<uint8_t>(c, kConfidenceLecturer - 1));
				}
				fractional += a != 0 && a != 255;
			}
		EXPECT_GT(fractional, 50u) << "smoothing " << smoothing;
	}
}

// The band scan's row (algo/band_scan.hpp) on every path: the same band,
// the same alpha, on a trimap that is mostly seeds with short band runs at
// every position of a 16-label block.
TEST(SioxRefiner, EveryKernelPathGivesTheSameAlpha)
{
	std::mt19937 random(23);
	Gray8Image trimap(kW, kH), evidence(kW, kH);
	for (size_t i = 0; i < trimap.size(); ++i) {
		trimap.data()[i] = random() % 2 ? kTrimapBoard : kTrimapLecturer;
		evidence.data()[i] = uint8_t(1 + random() % 255);
	}
	for (int run = 0; run < 300; ++run) {
		const int x = int(random() % (kW - 8)), y = int(random() % kH), n = 1 + int(random() % 8);
		fill(trimap, x, y, x + n, y + 1, run % 2 ? kTrimapUndecided : kTrimapInRange);
	}
	Gray8Image reference;
	size_t referenceBand = 0;
	for (KernelPath path : simd_test::kAllPaths) {
		SioxRefiner refiner;
		refiner.setKernelPath(path);
		RgbImage colour(kW, kH);
		MapEvidence fake(evidence);
		Gray8Image alpha;
		refiner.refine(colour, trimap, { 0, 0, kW, kH }, fake, alpha);
		if (path == KernelPath::C) {
			reference = alpha;
			referenceBand = refiner.bandPixels();
			EXPECT_GT(referenceBand, 600u);
			continue;
		}
		EXPECT_EQ(refiner.bandPixels(), referenceBand) << simd_test::pathName(path);
		EXPECT_EQ(alpha, reference) << simd_test::pathName(path);
	}
}
