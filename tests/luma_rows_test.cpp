// The guided filter's luma row (algo/luma_rows.hpp): the C row against a
// double reference (R + 2 G + B) / 4, rounded half up (exact: the sum is an
// integer), and the SSE2 and NEON rows against the C row bit for bit, for
// any pixels, runs of every length about the vector steps, unaligned.
#include "algo/luma_rows.hpp"
#include "tests/simd_paths.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

using namespace depthkey;

TEST(LumaRows, TheCRowIsTheRoundedWeightedMean)
{
	std::vector<Rgb8> colour;
	for (int r = 0; r < 256; r += 5)
		for (int g = 0; g < 256; g += 3)
			for (int b = 0; b < 256; b += 7)
				colour.push_back({ uint8_t(r), uint8_t(g), uint8_t(b) });
	colour.push_back({ 255, 255, 255 });
	std::vector<uint8_t> luma(colour.size());
	lumaRow_C(colour.data(), int(colour.size()), luma.data());
	for (size_t i = 0; i < colour.size(); ++i) {
		const Rgb8 c = colour[i];
		ASSERT_EQ(luma[i], int(std::floor((c.r + 2.0 * c.g + c.b) / 4.0 + 0.5))) << i;
	}
}

TEST(LumaRows, EveryPathGivesTheCRowsBytes)
{
	std::mt19937 rng(15);
	size_t compared = 0;
	for (int n : { 0, 1, 15, 16, 17, 18, 19, 33, 34, 35, 64, 101 })
		for (int offset : { 0, 1, 5 }) {
			std::vector<Rgb8> colour(size_t(n + offset));
			for (Rgb8 &c : colour)
				c = { uint8_t(rng()), uint8_t(rng()), uint8_t(rng()) };
			std::vector<uint8_t> want(size_t(n) + 1, 7), got(size_t(n) + 1);
			lumaRow_C(colour.data() + offset, n, want.data());
			for (KernelPath path : simd_test::kAllPaths) {
				std::fill(got.begin(), got.end(), uint8_t(7)); // the one past n stays
				lumaRow(path)(colour.data() + offset, n, got.data());
				ASSERT_EQ(got, want) << simd_test::pathName(path) << " n " << n << " offset " << offset;
			}
			compared += size_t(n);
		}
	EXPECT_GT(compared, 1000u);
}
