// The colour histogram whose old samples fade (algo/decaying_histogram.hpp)
// against a floating-point model in which every bin is multiplied by
// (1 - rate) each frame: the same proportions, through its rescaling, with
// the total bounded however long it runs.
#include "algo/decaying_histogram.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

using namespace depthkey;

namespace {

// Frame f adds first(f) samples of colour 1 and second(f) of colour 2, to
// the histogram and to the model; returns the largest relative error of
// colour 1's share seen after any frame.
template<typename First, typename Second>
double worstShareError(double rate, int frames, First first, Second second)
{
	DecayingHistogram histogram;
	histogram.setRate(rate);
	double model1 = 0, model2 = 0, worst = 0;
	for (int f = 0; f < frames; ++f) {
		model1 *= 1.0 - rate;
		model2 *= 1.0 - rate;
		for (int i = 0; i < first(f); ++i)
			histogram.add(1);
		for (int i = 0; i < second(f); ++i)
			histogram.add(2);
		model1 += first(f);
		model2 += second(f);
		const double share = double(histogram.bin(1)) / double(histogram.bin(1) + histogram.bin(2));
		const double expected = model1 / (model1 + model2);
		worst = std::max(worst, std::fabs(share - expected) / expected);
		EXPECT_EQ(histogram.total(), uint64_t(histogram.bin(1)) + histogram.bin(2)) << "frame " << f;
		histogram.endFrame();
	}
	return worst;
}

} // namespace

TEST(DecayingHistogram, FadesAsTheFloatingPointModelThroughItsRescaling)
{
	// Colour 1 first dominates, then fades out while colour 2 comes in:
	// 300 frames at rate 0.1 rescale by 256 every ~50 frames.
	auto first = [](int f) { return f < 100 ? 400 : 20; };
	auto second = [](int f) { return f < 100 ? 10 : 300; };
	for (double rate : { 0.02, 0.1, 0.3 }) {
		double worst = worstShareError(rate, 300, first, second);
		std::printf("rate %.2f: worst relative error of the share %.5f\n", rate, worst);
		EXPECT_LE(worst, 0.01) << "rate " << rate;
	}
}

TEST(DecayingHistogram, RateZeroKeepsEverythingWithinBounds)
{
	// 4000 frames of 5000 samples: far more than the total may hold, so it
	// is halved now and then, keeping the proportions.
	double worst = worstShareError(0.0, 4000, [](int) { return 3000; }, [](int) { return 2000; });
	EXPECT_LE(worst, 0.001);
	DecayingHistogram histogram;
	for (int f = 0; f < 4000; ++f) {
		for (int i = 0; i < 5000; ++i)
			histogram.add(uint32_t(i % 7));
		histogram.endFrame();
		ASSERT_LE(histogram.total(), uint64_t(1) << 31) << "frame " << f;
	}
}

TEST(DecayingHistogram, RateOneCountsOnlyTheCurrentFrame)
{
	DecayingHistogram histogram;
	histogram.setRate(1.0);
	histogram.add(5);
	histogram.add(5);
	EXPECT_GT(histogram.bin(5), 0u);
	histogram.endFrame();
	EXPECT_EQ(histogram.total(), 0u);
	histogram.add(6);
	EXPECT_EQ(histogram.bin(5), 0u);
	EXPECT_GT(histogram.bin(6), 0u);
}

TEST(DecayingHistogram, CollectsTheNonEmptyBinsWithTheirWeights)
{
	DecayingHistogram histogram;
	histogram.setRate(0.5);
	for (uint32_t colour : { 3u, 3u, 900u })
		histogram.add(colour);
	histogram.endFrame();
	histogram.add(900);
	QuantisedLab lab;
	std::vector<WeightedLab> points(kQuantisedColours);
	ASSERT_EQ(histogram.collect(lab, points.data()), 2u);
	EXPECT_EQ(points[0].weight, histogram.bin(3));
	EXPECT_EQ(points[1].weight, histogram.bin(900));
	EXPECT_EQ(points[0].lab.l, lab[3].l);
	// Colour 900, one sample a frame ago and one now, weighs 1/2 + 1; colour
	// 3, two samples a frame ago, weighs 2 x 1/2.
	EXPECT_NEAR(double(points[1].weight) / points[0].weight, 1.5, 0.01);
	histogram.clear();
	EXPECT_EQ(histogram.collect(lab, points.data()), 0u);
}
