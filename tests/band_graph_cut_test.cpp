// The band's minimum cut (algo/band_graph_cut.hpp): against a brute-force
// minimum of the same energy in double precision (every labelling of a small
// band), and on a band whose evidence is ambiguous, where it must follow the
// colour edge.
#include "algo/band_graph_cut.hpp"
#include "algo/siox_classifier.hpp"
#include "algo/trimap.hpp"
#include "settings/settings.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

using namespace depthkey;

namespace {

// The band: every pixel of the trimap that is neither core nor board, as
// SioxRefiner collects it (row-major runs).
std::vector<BandSpan> spansOf(const Gray8Image &trimap)
{
	std::vector<BandSpan> spans;
	int first = 0;
	for (int y = 0; y < trimap.height(); ++y)
		for (int x = 0; x < trimap.width();) {
			auto seed = [&](int xx) { return trimap.at(xx, y) == kTrimapBoard || trimap.at(xx, y) == kTrimapLecturer; };
			if (seed(x)) {
				++x;
				continue;
			}
			BandSpan s{ y, x, x, first };
			while (x < trimap.width() && !seed(x))
				++x;
			s.x1 = x;
			first += s.x1 - s.x0;
			spans.push_back(s);
		}
	return spans;
}

// The energy of a labelling (1 = lecturer) of the whole image, in double:
// data terms of band pixels plus smoothness * exp(-d2 / (2 sigma^2)) for every
// 4-neighbour pair labelled apart (seeds labelled as they are).
double energy(const RgbImage &colour, const Gray8Image &trimap, const std::vector<uint8_t> &confidence,
	      const std::vector<int> &label, double smoothness, double sigma)
{
	const int w = colour.width(), h = colour.height();
	double e = 0;
	int k = 0;
	for (int y = 0; y < h; ++y)
		for (int x = 0; x < w; ++x) {
			const uint8_t t = trimap.at(x, y);
			if (t != kTrimapBoard && t != kTrimapLecturer) {
				const double data = double(confidence[size_t(k++)]) - kConfidenceLecturer;
				e += label[size_t(y * w + x)] ? std::max(-data, 0.0) : std::max(data, 0.0);
			}
			for (auto [dx, dy] : { std::pair{ 1, 0 }, std::pair{ 0, 1 } }) {
				const int xx = x + dx, yy = y + dy;
				if (xx >= w || yy >= h || label[size_t(y * w + x)] == label[size_t(yy * w + xx)])
					continue;
				const Rgb8 a = colour.at(x, y), b = colour.at(xx, yy);
				const double d2 = double(a.r - b.r) * (a.r - b.r) + double(a.g - b.g) * (a.g - b.g) +
						  double(a.b - b.b) * (a.b - b.b);
				e += smoothness * std::exp(-d2 / (2 * sigma * sigma));
			}
		}
	return e;
}

} // namespace

TEST(BandGraphCut, ReachesTheBruteForceMinimumOfItsEnergy)
{
	// A 5 x 4 image: a core column at the left, board at the right, a band
	// of 12 pixels (4 rows x 3) between, random colours and confidences.
	// Every one of the 2^12 labellings of the band is tried in double.
	std::mt19937 random(11);
	for (int trial = 0; trial < 40; ++trial) {
		const int w = 5, h = 4;
		RgbImage colour(w, h);
		Gray8Image trimap(w, h, kTrimapUndecided);
		for (int y = 0; y < h; ++y) {
			trimap.at(0, y) = kTrimapLecturer;
			trimap.at(w - 1, y) = kTrimapBoard;
			for (int x = 0; x < w; ++x) {
				const uint8_t v = uint8_t(random() % 60);
				colour.at(x, y) = { uint8_t(v + random() % 8), uint8_t(v + random() % 8), v };
			}
		}
		const std::vector<BandSpan> spans = spansOf(trimap);
		const int n = spans.back().first + spans.back().x1 - spans.back().x0;
		ASSERT_EQ(n, 12);
		std::vector<uint8_t> confidence(static_cast<size_t>(n)), decisions(static_cast<size_t>(n));
		for (uint8_t &c : confidence)
			c = uint8_t(1 + random() % 255);
		const int smoothness = 20 + int(random() % 200), sigma = 3 + int(random() % 10);
		BandGraphCut cut;
		cut.configure(smoothness, sigma);
		cut.cut(colour, trimap, spans, confidence.data(), decisions.data());

		auto labelling = [&](auto bandLabel) {
			std::vector<int> label(size_t(w * h));
			int k = 0;
			for (int y = 0; y < h; ++y)
				for (int x = 0; x < w; ++x) {
					const uint8_t t = trimap.at(x, y);
					label[size_t(y * w + x)] = t == kTrimapLecturer ? 1 : t == kTrimapBoard ? 0 : bandLabel(k++);
				}
			return label;
		};
		const double got = energy(colour, trimap, confidence, labelling([&](int k) { return decisions[size_t(k)] ? 1 : 0; }),
					  smoothness, sigma);
		double best = std::numeric_limits<double>::max();
		for (unsigned bits = 0; bits < (1u << n); ++bits)
			best = std::min(best, energy(colour, trimap, confidence,
						     labelling([&](int k) { return int((bits >> k) & 1); }), smoothness, sigma));
		// Tolerance: each edge weight is rounded to an integer (at most 0.5
		// off), and there are 25 pairs a labelling can cut (17 inside the
		// band, 8 to the seeds); the integer optimum's real energy is within
		// 0.5 * 25 of the integer energy, which is at most the real optimum's
		// integer energy, itself within 0.5 * 25 of the real optimum.
		EXPECT_LE(got, best + 25.0) << "trial " << trial;
		EXPECT_GE(got, best - 1e-9);
	}
}

TEST(BandGraphCut, FollowsTheColourEdgeWhereTheEvidenceIsAmbiguous)
{
	// 40 x 20: core at x < 5, board at x >= 35; a dark sleeve (30, 40, 36)
	// up to x = 22 on the dark board (24, 28, 28) beyond, with noise; the
	// evidence says nothing (128 +- noise) across the band.
	std::mt19937 random(5);
	std::normal_distribution<double> noise(0, 3);
	const int w = 40, h = 20;
	RgbImage colour(w, h);
	Gray8Image trimap(w, h, kTrimapUndecided);
	for (int y = 0; y < h; ++y)
		for (int x = 0; x < w; ++x) {
			const bool sleeve = x < 22;
			auto level = [&](int v) { return uint8_t(std::clamp(int(std::lround(v + noise(random))), 0, 255)); };
			colour.at(x, y) = sleeve ? Rgb8{ level(30), level(40), level(36) } : Rgb8{ level(24), level(28), level(28) };
			trimap.at(x, y) = x < 5 ? kTrimapLecturer : x >= 35 ? kTrimapBoard : kTrimapUndecided;
		}
	const std::vector<BandSpan> spans = spansOf(trimap);
	const size_t n = size_t(spans.back().first + spans.back().x1 - spans.back().x0);
	std::vector<uint8_t> confidence(n), decisions(n);
	for (uint8_t &c : confidence)
		c = uint8_t(std::clamp(128 + int(std::lround(noise(random) * 10)), 1, 255));
	BandGraphCut cut;
	cut.configure(Settings{}.decision.cutSmoothness, Settings{}.decision.cutEdgeSigma);
	cut.cut(colour, trimap, spans, confidence.data(), decisions.data());
	int wrong = 0;
	for (const BandSpan &s : spans)
		for (int x = s.x0; x < s.x1; ++x)
			wrong += (decisions[size_t(s.first + x - s.x0)] != 0) != (x < 22);
	EXPECT_LE(wrong, int(n) / 50) << "of " << n; // the edge within a pixel or so
	// Off, per pixel on that noise, half would be wrong: the cut's doing.
	int perPixelWrong = 0;
	for (const BandSpan &s : spans)
		for (int x = s.x0; x < s.x1; ++x)
			perPixelWrong += (confidence[size_t(s.first + x - s.x0)] >= kConfidenceLecturer) != (x < 22);
	EXPECT_GT(perPixelWrong, int(n) / 4);
}

TEST(BandGraphCut, EdgeWeightFallsWithColourDistanceAndOffMeansOff)
{
	BandGraphCut cut;
	cut.configure(1000, 7);
	EXPECT_TRUE(cut.enabled());
	const Rgb8 a{ 30, 40, 36 };
	EXPECT_EQ(cut.edgeWeight(a, a), 1000);
	EXPECT_NEAR(cut.edgeWeight(a, Rgb8{ 37, 40, 36 }), 1000 * std::exp(-49.0 / 98.0), 0.5);
	EXPECT_GT(cut.edgeWeight(a, Rgb8{ 33, 40, 36 }), cut.edgeWeight(a, Rgb8{ 40, 40, 36 }));
	EXPECT_EQ(cut.edgeWeight(a, Rgb8{ 90, 40, 36 }), 0);
	cut.configure(0, 7);
	EXPECT_FALSE(cut.enabled());
}

TEST(BandGraphCut, IsolatedBandPixelsAreDecidedByTheirOwnTerms)
{
	// A band of single pixels between seeds (no two touch): no edge in the
	// graph, which OpenCV's max-flow refuses; each is decided by its
	// confidence and the pull of its seed neighbours.
	const int w = 9, h = 3;
	RgbImage colour(w, h, Rgb8{ 40, 40, 40 });
	Gray8Image trimap(w, h, kTrimapBoard);
	trimap.at(2, 1) = trimap.at(6, 1) = kTrimapUndecided;
	trimap.at(5, 1) = kTrimapLecturer; // pulls (6, 1) to the lecturer
	const std::vector<BandSpan> spans = spansOf(trimap);
	ASSERT_EQ(spans.size(), 2u);
	const uint8_t confidence[2] = { 250, 140 };
	uint8_t decisions[2] = { 7, 7 };
	BandGraphCut cut;
	cut.configure(1000, 7);
	cut.cut(colour, trimap, spans, confidence, decisions);
	EXPECT_EQ(decisions[0], 0);   // four board neighbours outweigh a sure colour
	EXPECT_EQ(decisions[1], 0);   // three board, one lecturer neighbour
	trimap.at(7, 1) = trimap.at(6, 0) = trimap.at(6, 2) = kTrimapLecturer;
	cut.cut(colour, trimap, spans, confidence, decisions);
	EXPECT_EQ(decisions[1], 255); // enclosed by the lecturer
}

TEST(BandGraphCut, TheSameCutWithTheNarrowAndTheWideWeights)
{
	// A band of 66 000 pixels (330 x 200), a clean colour edge at x = 170,
	// evidence that says nothing: at cut_smoothness 5000 the flow's bound
	// (66 000 * (128 + 4 * 5000)) fits 32-bit weights, at 10000 it does not
	// and the graph is built with 64-bit ones. Both must cut along the edge
	// (every weight is the smoothness or 0 there: any other cut costs rows
	// of it), so the two cuts are the same one.
	const int w = 340, h = 200, edge = 170;
	RgbImage colour(w, h);
	Gray8Image trimap(w, h);
	for (int y = 0; y < h; ++y)
		for (int x = 0; x < w; ++x) {
			colour.at(x, y) = x < edge ? Rgb8{ 30, 40, 36 } : Rgb8{ 200, 200, 190 };
			trimap.at(x, y) = x < 5 ? kTrimapLecturer : x >= 335 ? kTrimapBoard : kTrimapUndecided;
		}
	const std::vector<BandSpan> spans = spansOf(trimap);
	const size_t n = size_t(spans.back().first + spans.back().x1 - spans.back().x0);
	ASSERT_EQ(n, 66000u);
	std::vector<uint8_t> confidence(n), narrow(n), wide(n);
	for (size_t k = 0; k < n; ++k)
		confidence[k] = uint8_t(120 + k % 17); // 120..136: no side
	BandGraphCut cut;
	cut.configure(5000, 7);
	cut.cut(colour, trimap, spans, confidence.data(), narrow.data());
	cut.configure(10000, 7);
	cut.cut(colour, trimap, spans, confidence.data(), wide.data());
	EXPECT_EQ(narrow, wide);
	int wrong = 0;
	for (const BandSpan &s : spans)
		for (int x = s.x0; x < s.x1; ++x)
			wrong += (wide[size_t(s.first + x - s.x0)] != 0) != (x < edge);
	EXPECT_EQ(wrong, 0);
}
