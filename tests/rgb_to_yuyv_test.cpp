// RGB -> YUYV (hal/v4l2/rgb_to_yuyv.hpp) against BT.601 limited range in
// doubles. Tolerance: within 1 level per component (Q16 coefficients, one
// rounding: the fixed point is off the double by at most 0.5 + 510 x 2^-17
// before rounding). The error histogram is printed. The SSE2 and NEON rows
// against the C row bit for bit, odd widths and unaligned pointers.
#include <gtest/gtest.h>

#include "hal/v4l2/rgb_to_yuyv.hpp"
#include "hal/v4l2/yuv_to_rgb.hpp"
#include "tests/simd_paths.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

using namespace depthkey;

namespace {

struct Ycc {
	double y, cb, cr;
};

// From the standard's constants (Kr 0.299, Kb 0.114; 219 and 224 levels).
Ycc referenceYcc(double r, double g, double b)
{
	double y = 0.299 * r + 0.587 * g + 0.114 * b;
	return { 16 + 219.0 / 255.0 * y, 128 + 224.0 / 255.0 * (b - y) / 1.772,
		 128 + 224.0 / 255.0 * (r - y) / 1.402 };
}

} // namespace

TEST(RgbToYuyv, EveryColourWithinOneLevelOfDouble)
{
	// Each of the 2^24 colours as a pair with itself: Y, Cb and Cr of one colour.
	long histogram[3] = {};
	double worst = 0;
	for (int r = 0; r < 256; r++)
		for (int g = 0; g < 256; g++)
			for (int b = 0; b < 256; b++) {
				const Rgb8 pair[2] = { { uint8_t(r), uint8_t(g), uint8_t(b) },
						       { uint8_t(r), uint8_t(g), uint8_t(b) } };
				uint8_t out[4];
				rgbToYuyvRow_C(pair, out, 2);
				Ycc want = referenceYcc(r, g, b);
				for (auto [got, w] : { std::pair<int, double>{ out[0], want.y }, { out[1], want.cb },
						       { out[2], want.y }, { out[3], want.cr } }) {
					double e = std::fabs(got - w);
					worst = std::max(worst, e);
					histogram[e <= 0.5 + 1e-9 ? 0 : e <= 1.0 ? 1 : 2]++;
				}
			}
	std::printf("RGB->YUYV |error| histogram over 4 x 2^24 components: <=0.5 (rounded right): %ld, "
		    "<=1: %ld, >1: %ld; worst %.3f\n",
		    histogram[0], histogram[1], histogram[2], worst);
	EXPECT_EQ(histogram[2], 0);
	EXPECT_LE(worst, 1.0);
}

TEST(RgbToYuyv, ChromaIsThePairsMeanColour)
{
	std::mt19937 rng(13);
	std::uniform_int_distribution<int> level(0, 255);
	double worst = 0;
	for (int i = 0; i < 200000; i++) {
		Rgb8 pair[2];
		for (Rgb8 &p : pair)
			p = { uint8_t(level(rng)), uint8_t(level(rng)), uint8_t(level(rng)) };
		uint8_t out[4];
		rgbToYuyvRow_C(pair, out, 2);
		Ycc a = referenceYcc(pair[0].r, pair[0].g, pair[0].b);
		Ycc b = referenceYcc(pair[1].r, pair[1].g, pair[1].b);
		worst = std::max({ worst, std::fabs(out[0] - a.y), std::fabs(out[2] - b.y),
				   std::fabs(out[1] - (a.cb + b.cb) / 2), std::fabs(out[3] - (a.cr + b.cr) / 2) });
	}
	EXPECT_LE(worst, 1.0);
}

TEST(RgbToYuyv, BlackWhiteAndGreyAreExact)
{
	const Rgb8 row[4] = { { 0, 0, 0 }, { 0, 0, 0 }, { 255, 255, 255 }, { 128, 128, 128 } };
	uint8_t out[8];
	rgbToYuyvRow_C(row, out, 4);
	EXPECT_EQ(out[0], 16);
	EXPECT_EQ(out[1], 128);
	EXPECT_EQ(out[2], 16);
	EXPECT_EQ(out[3], 128);
	EXPECT_EQ(out[4], 235);
	EXPECT_EQ(out[6], 126); // 16 + 219 x 128/255 = 125.9
	EXPECT_EQ(out[5], 128);
	EXPECT_EQ(out[7], 128);
}

TEST(RgbToYuyv, OddWidthRepeatsTheLastPixelAndFramesRoundTrip)
{
	// 5 pixels -> 3 pairs, the last pixel paired with itself; back through
	// the capture side's converter within a few levels (two roundings and
	// chroma shared by the pair).
	RgbImage image(5, 3);
	std::mt19937 rng(7);
	for (int y = 0; y < 3; y++)
		for (int x = 0; x < 5; x++) {
			uint8_t v = static_cast<uint8_t>(40 + rng() % 170);
			image.at(x, y) = { v, v, v }; // grey: no chroma to share
		}
	ASSERT_EQ(yuyvWidth(5), 6);
	ASSERT_EQ(yuyvFrameBytes(5, 3), 36u);
	std::vector<uint8_t> yuyv(36, 0xAA);
	EXPECT_EQ(rgbToYuyv(image, yuyv.data(), 35), -EMSGSIZE);
	ASSERT_EQ(rgbToYuyv(image, yuyv.data(), yuyv.size()), 0);
	for (int y = 0; y < 3; y++) {
		const uint8_t *row = yuyv.data() + 12 * y;
		EXPECT_EQ(row[8], row[10]) << "the odd last pixel repeated";
		Rgb8 back[6];
		yuyvToRgbRow(row, back, 6);
		for (int x = 0; x < 5; x++)
			EXPECT_LE(std::abs(back[x].r - image.at(x, y).r), 1) << x << "," << y;
	}
}

TEST(RgbToYuyv, SimdRowsEqualTheCRowBitForBit)
{
	struct SimdRow {
		const char *name;
		void (*row)(const Rgb8 *, uint8_t *, int);
	};
	const SimdRow kSimdRows[] = { { "SSE2", rgbToYuyvRow_SSE2 }, { "NEON", rgbToYuyvRow_NEON } };
	std::mt19937 rng(5);
	size_t compared = 0;
	for (int width : { 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 15, 16, 17, 31, 33, 100, 639, 640, 641, 1919, 1920 }) {
		for (int offset = 0; offset < 3; ++offset) { // Rgb8 offsets 1, 2 and odd output bytes: unaligned
			std::vector<Rgb8> in(static_cast<size_t>(width) + 3);
			for (Rgb8 &p : in)
				p = { uint8_t(rng()), uint8_t(rng()), uint8_t(rng()) };
			if (offset == 2) // the extremes too
				for (size_t i = 0; i < in.size(); i++)
					in[i] = i % 3 ? Rgb8{ 255, 255, 255 } : Rgb8{ 0, 255, 0 };
			std::vector<uint8_t> outC(static_cast<size_t>(yuyvWidth(width)) * 2 + 4, 0x55);
			rgbToYuyvRow_C(in.data() + offset, outC.data() + offset, width);
			for (const SimdRow &simd : kSimdRows) {
				std::vector<uint8_t> outSimd(outC.size(), 0x55);
				simd.row(in.data() + offset, outSimd.data() + offset, width);
				ASSERT_EQ(outC, outSimd) << simd.name << " width " << width << " offset " << offset;
			}
			compared += static_cast<size_t>(width);
		}
	}
	EXPECT_GT(compared, 10000u);
	// Whole frames on every path.
	RgbImage image(641, 7);
	for (size_t i = 0; i < image.size(); i++)
		image.data()[i] = { uint8_t(rng()), uint8_t(rng()), uint8_t(rng()) };
	std::vector<uint8_t> c(yuyvFrameBytes(641, 7)), simd(c.size());
	ASSERT_EQ(rgbToYuyv(image, c.data(), c.size(), KernelPath::C), 0);
	for (KernelPath path : simd_test::kSimdPaths) {
		ASSERT_EQ(rgbToYuyv(image, simd.data(), simd.size(), path), 0);
		EXPECT_EQ(c, simd) << simd_test::pathName(path);
	}
}
