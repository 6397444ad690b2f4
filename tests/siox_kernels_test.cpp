// The fixed-point SIOX kernels against the double reference (siox_reference):
// Lab conversion (max error stated), signatures on random samples, the k-d
// nearest search, the integer square root and the per-colour decision.
#include "algo/colour_signature.hpp"
#include "algo/lab_converter.hpp"
#include "algo/quantised_colour.hpp"
#include "algo/siox_classifier.hpp"
#include "tests/siox_reference.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <algorithm>
#include <random>

using namespace depthkey;
using namespace depthkey::test;

TEST(LabConverter, FixedPointWithinThreeHundredthsOfTheDoubleFormula)
{
	// Every 3rd code value per channel (and 255): 87^3 colours.
	LabConverter converter;
	double maxError[3] = {};
	int histogram[4] = {}; // |error| in Lab16 units: 0, 1, 2, >2
	for (int r = 0; r <= 255; r += (r == 252 ? 3 : 3))
		for (int g = 0; g <= 255; g += 3)
			for (int b = 0; b <= 255; b += 3) {
				Lab16 fixed = converter.convert(uint8_t(r), uint8_t(g), uint8_t(b));
				LabD ref = referenceLab({ uint8_t(r), uint8_t(g), uint8_t(b) });
				int16_t got[3] = { fixed.l, fixed.a, fixed.b };
				for (int k = 0; k < 3; ++k) {
					double err = std::fabs(got[k] / 100.0 - ref[k]);
					maxError[k] = std::max(maxError[k], err);
					histogram[std::min(3, int(std::lround(err * 100.0)))]++;
				}
			}
	std::printf("Lab fixed vs double, max |error|: L %.4f a %.4f b %.4f; units of 0.01: 0:%d 1:%d 2:%d >2:%d\n",
		    maxError[0], maxError[1], maxError[2], histogram[0], histogram[1], histogram[2], histogram[3]);
	for (double e : maxError)
		EXPECT_LE(e, 0.03);
}

TEST(LabConverter, WhiteAndBlackAreExact)
{
	LabConverter converter;
	EXPECT_EQ(converter.convert(255, 255, 255), (Lab16{ 10000, 0, 0 }));
	EXPECT_EQ(converter.convert(0, 0, 0), (Lab16{ 0, 0, 0 }));
}

namespace {

// Samples around a few colours, integer Lab16 (the reference sees the same
// values as doubles, so the clustering must agree exactly).
std::vector<WeightedLab> randomSamples(std::mt19937 &rng, int count)
{
	std::uniform_int_distribution<int> centre(0, 4), spread(-400, 400), weight(1, 5);
	const Lab16 centres[5] = { { 5000, 2000, 1500 }, { 3000, -3000, 1000 }, { 8000, 0, 5000 },
				   { 2000, 500, -4000 }, { 6500, 4000, -1000 } };
	std::vector<WeightedLab> out;
	for (int i = 0; i < count; ++i) {
		Lab16 c = centres[centre(rng)];
		out.push_back({ { int16_t(c.l + spread(rng)), int16_t(c.a + spread(rng)), int16_t(c.b + spread(rng)) },
				uint32_t(weight(rng)) });
	}
	return out;
}

std::vector<WeightedLabD> asReference(const std::vector<WeightedLab> &points)
{
	std::vector<WeightedLabD> out;
	for (const auto &p : points)
		out.push_back({ { double(p.lab.l), double(p.lab.a), double(p.lab.b) }, double(p.weight) });
	return out;
}

} // namespace

TEST(ColourSignature, MatchesTheReferenceClusteringExactlyWithIntegerCentroids)
{
	std::mt19937 rng(11);
	for (int trial = 0; trial < 5; ++trial) {
		auto samples = randomSamples(rng, 3000 + 1000 * trial);
		auto reference = referenceSignature(asReference(samples), { 64, 128, 256 }, true);
		ColourSignature signature;
		auto work = samples;
		signature.build(work.data(), work.size());
		ASSERT_EQ(signature.size(), reference.size()) << "trial " << trial;
		ASSERT_GT(signature.size(), 10u);
		// Same clusters; centroids differ by rounding only (<= 0.5 units each).
		for (const auto &ref : reference) {
			bool found = false;
			for (size_t i = 0; i < signature.size() && !found; ++i) {
				const WeightedLab &c = signature.centroid(i);
				found = std::fabs(c.lab.l - ref.lab[0]) <= 0.5 && std::fabs(c.lab.a - ref.lab[1]) <= 0.5 &&
					std::fabs(c.lab.b - ref.lab[2]) <= 0.5 && double(c.weight) == ref.weight;
			}
			EXPECT_TRUE(found) << "reference centroid " << ref.lab[0] << "," << ref.lab[1] << "," << ref.lab[2];
		}
	}
}

TEST(ColourSignature, NearestDistancesAgreeWithTheUnroundedReference)
{
	// Without the rounding emulation the stage-two splits may differ where a
	// centroid sits on a pivot; the signatures still describe the same
	// colours: the nearest distance of any colour differs by little.
	std::mt19937 rng(12);
	auto samples = randomSamples(rng, 8000);
	auto reference = referenceSignature(asReference(samples), { 64, 128, 256 });
	ColourSignature signature;
	signature.build(samples.data(), samples.size());
	std::uniform_int_distribution<int> l(0, 10000), ab(-9000, 9000);
	double worst = 0;
	for (int i = 0; i < 5000; ++i) {
		Lab16 q{ int16_t(l(rng)), int16_t(ab(rng)), int16_t(ab(rng)) };
		double fixed = std::sqrt(double(signature.nearest(q)));
		double ref = std::sqrt(referenceNearest(reference, { double(q.l), double(q.a), double(q.b) }));
		worst = std::max(worst, std::fabs(fixed - ref));
	}
	std::printf("signature nearest distance, fixed vs unrounded reference: max |diff| %.2f Lab units "
		    "(%zu vs %zu centroids)\n", worst / 100.0, signature.size(), reference.size());
	EXPECT_LE(worst, 300.0); // 3 Lab units: the size of one cluster cell (2.56 on b)
}

TEST(ColourSignature, DropsClustersUnderOneThousandthOfTheSamples)
{
	// 1 of 1001 is under 0.1 %.
	std::vector<WeightedLab> points = { { { 5000, 0, 0 }, 1000 }, { { 9000, 0, 0 }, 1 } };
	ColourSignature signature;
	signature.build(points.data(), points.size());
	ASSERT_EQ(signature.size(), 1u);
	EXPECT_EQ(signature.centroid(0).lab, (Lab16{ 5000, 0, 0 }));
	points = { { { 5000, 0, 0 }, 998 }, { { 9000, 0, 0 }, 1 }, { { 9000, 0, 0 }, 1 } };
	signature.build(points.data(), points.size());
	EXPECT_EQ(signature.size(), 2u); // 2 of 1000 = 0.2 % survives
}

TEST(ColourSignature, TreeSearchEqualsBruteForce)
{
	std::mt19937 rng(5);
	auto samples = randomSamples(rng, 20000);
	ColourSignature signature;
	signature.build(samples.data(), samples.size());
	std::uniform_int_distribution<int> l(0, 10000), ab(-9000, 9000);
	for (int i = 0; i < 20000; ++i) {
		Lab16 q{ int16_t(l(rng)), int16_t(ab(rng)), int16_t(ab(rng)) };
		ASSERT_EQ(signature.nearest(q), signature.nearestBruteForce(q));
	}
}

TEST(SioxClassifier, IntegerSquareRootIsFloorOfSqrt)
{
	std::mt19937 rng(3);
	std::uniform_int_distribution<uint32_t> any;
	for (uint32_t v : { 0u, 1u, 2u, 3u, 4u, 15u, 16u, 17u, 0xFFFFFFFFu, 0xFFFE0001u })
		EXPECT_EQ(integerSqrt(v), uint32_t(std::floor(std::sqrt(double(v)))));
	for (int i = 0; i < 100000; ++i) {
		uint32_t v = any(rng);
		ASSERT_EQ(integerSqrt(v), uint32_t(std::floor(std::sqrt(double(v))))) << v;
	}
}

TEST(SioxClassifier, CachedDecisionMatchesTheDoubleDecision)
{
	// The cache decides per quantised cell, with Lab16 arithmetic; the
	// reference decides with the colour's exact double Lab and the same
	// centroids. Moving a colour by d (to its cell centre) changes each
	// distance by at most d, so the two may only differ where
	// |dFg - dBg| <= 2 d; anywhere else they must agree.
	std::mt19937 rng(9);
	std::normal_distribution<double> n(0.0, 8.0);
	auto around = [&](Rgb8 c) {
		auto ch = [&](int v) { return uint8_t(std::clamp(int(std::lround(v + n(rng))), 0, 255)); };
		return Rgb8{ ch(c.r), ch(c.g), ch(c.b) };
	};
	QuantisedLab table;
	SioxClassifier classifier(table);
	std::vector<WeightedLab> fg, bg;
	for (int i = 0; i < 4000; ++i) {
		Rgb8 f = around(i % 2 ? Rgb8{ 150, 40, 50 } : Rgb8{ 224, 172, 140 });
		Rgb8 b = around(i % 3 ? Rgb8{ 30, 60, 40 } : Rgb8{ 235, 235, 230 });
		fg.push_back({ table[quantiseColour(f)], 1 });
		bg.push_back({ table[quantiseColour(b)], 1 });
	}
	classifier.lecturer().build(fg.data(), fg.size());
	classifier.board().build(bg.data(), bg.size());
	classifier.signaturesChanged();
	auto asDouble = [](const ColourSignature &sig) {
		std::vector<WeightedLabD> out;
		for (size_t i = 0; i < sig.size(); ++i) {
			Lab16 c = sig.centroid(i).lab;
			out.push_back({ { c.l / 100.0, c.a / 100.0, c.b / 100.0 }, 1.0 });
		}
		return out;
	};
	auto fgSig = asDouble(classifier.lecturer()), bgSig = asDouble(classifier.board());

	std::uniform_int_distribution<int> byte(0, 255);
	int agree = 0, total = 0, allowed = 0;
	for (int i = 0; i < 30000; ++i) {
		Rgb8 c{ uint8_t(byte(rng)), uint8_t(byte(rng)), uint8_t(byte(rng)) };
		if (i % 2)
			c = around(i % 4 == 1 ? Rgb8{ 150, 40, 50 } : Rgb8{ 30, 60, 40 });
		bool fixedLecturer = classifier.confidence(quantiseColour(c)) >= kConfidenceLecturer;
		LabD lab = referenceLab(c), centre = referenceLab(quantisedCentre(quantiseColour(c)));
		double moved = std::sqrt((lab[0] - centre[0]) * (lab[0] - centre[0]) + (lab[1] - centre[1]) * (lab[1] - centre[1]) +
					 (lab[2] - centre[2]) * (lab[2] - centre[2]));
		double dFg = std::sqrt(referenceNearest(fgSig, lab)), dBg = std::sqrt(referenceNearest(bgSig, lab));
		++total;
		if (fixedLecturer == (dFg <= dBg)) {
			++agree;
			continue;
		}
		// + 0.03: Lab16 rounding of the colour and the centroids.
		if (std::fabs(dFg - dBg) <= 2.0 * moved + 0.03)
			++allowed;
		else
			ADD_FAILURE() << "decision differs away from the boundary: " << int(c.r) << "," << int(c.g) << ","
				      << int(c.b) << " dFg " << dFg << " dBg " << dBg << " moved " << moved;
	}
	std::printf("SIOX decision cached (quantised, fixed) vs double: %d of %d agree (%.3f %%), "
		    "%d differ within the quantisation margin\n", agree, total, 100.0 * agree / total, allowed);
	EXPECT_GE(double(agree) / total, 0.98);
}

TEST(SioxClassifier, ConfidenceIsConsistentWithTheDecision)
{
	QuantisedLab table;
	SioxClassifier classifier(table);
	std::vector<WeightedLab> fg = { { { 5000, 4000, 2000 }, 1 } }, bg = { { { 4000, -3000, 1000 }, 1 } };
	classifier.lecturer().build(fg.data(), fg.size());
	classifier.board().build(bg.data(), bg.size());
	classifier.signaturesChanged();
	EXPECT_EQ(classifier.decideLab({ 5000, 4000, 2000 }), 255);  // on the lecturer centroid
	EXPECT_EQ(classifier.decideLab({ 4000, -3000, 1000 }), 1);   // on the board centroid
	EXPECT_EQ(classifier.decideLab({ 4500, 500, 1500 }), 128);   // half way: lecturer (not larger)
	for (uint32_t q = 0; q < kQuantisedColours; q += 97) {
		uint32_t dFg = classifier.lecturer().nearest(table[q]), dBg = classifier.board().nearest(table[q]);
		uint8_t c = classifier.confidence(q);
		ASSERT_GE(c, 1);
		ASSERT_EQ(c >= kConfidenceLecturer, dFg <= dBg) << q;
	}
}

// A cell's Lab is its centre's conversion, asked for in any order (no
// table, no state: issue 15).
TEST(QuantisedLab, ACellIsItsCentreConverted)
{
	QuantisedLab lab;
	LabConverter converter;
	std::vector<uint32_t> order(kQuantisedColours);
	for (uint32_t i = 0; i < kQuantisedColours; ++i)
		order[i] = i;
	std::shuffle(order.begin(), order.end(), std::mt19937(15));
	size_t differ = 0;
	for (uint32_t i : order) {
		Rgb8 c = quantisedCentre(i);
		differ += !(lab[i] == converter.convert(c.r, c.g, c.b));
	}
	EXPECT_EQ(differ, 0u);
	// White is L* 100, black 0.
	EXPECT_EQ(lab[quantiseColour({ 255, 255, 255 })].l / 100, 99);
	EXPECT_EQ(lab[quantiseColour({ 0, 0, 0 })].l / 100, 0);
}
