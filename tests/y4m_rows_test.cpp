// The y4m row kernels against plain models: the 2x2 chroma mean (odd widths,
// an odd last row) and the rate written for a measured frame rate (issue 29).
#include "algo/y4m_rows.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using namespace depthkey;

TEST(Y4mRows, ChromaMeanRoundsLikeTheModelAtOddWidths)
{
	for (int width : { 1, 2, 3, 7, 16, 33 }) {
		std::vector<uint8_t> row0(width), row1(width);
		for (int x = 0; x < width; x++) {
			row0[x] = static_cast<uint8_t>(x * 37 + 5);
			row1[x] = static_cast<uint8_t>(255 - x * 19);
		}
		std::vector<uint8_t> out((width + 1) / 2, 0xee);
		subsampleChromaRow_C(row0.data(), row1.data(), width, out.data());
		for (int c = 0; c < (width + 1) / 2; c++) {
			const int x1 = std::min(2 * c + 1, width - 1); // the odd column with itself
			const double mean = (row0[2 * c] + row0[x1] + row1[2 * c] + row1[x1]) / 4.0;
			EXPECT_EQ(out[c], static_cast<int>(std::floor(mean + 0.5))) << width << " " << c;
		}
	}
}

TEST(Y4mRows, GreysKeepNeutralChroma)
{
	const uint8_t rgb[] = { 0, 0, 0, 128, 128, 128, 255, 255, 255 };
	uint8_t y[3], u[3], v[3];
	rgbToYuv444Row_C(rgb, 3, 3, y, u, v, nullptr);
	EXPECT_EQ(y[0], 0);
	EXPECT_EQ(y[2], 255);
	for (int i = 0; i < 3; i++) {
		EXPECT_EQ(u[i], 128);
		EXPECT_EQ(v[i], 128);
	}
}

TEST(Y4mRows, RateRationals)
{
	auto rate = [](double fps) {
		FrameRate r = y4mFrameRate(fps);
		return std::to_string(r.num) + ":" + std::to_string(r.den);
	};
	EXPECT_EQ(rate(25.0), "25:1");
	EXPECT_EQ(rate(10.03), "10:1");         // within 0.5%: whole
	EXPECT_EQ(rate(29.97), "30000:1001");   // NTSC
	EXPECT_EQ(rate(30.0), "30:1");
	EXPECT_EQ(rate(14.3), "143:10");        // a busy daemon's rate, to 1/1000
	EXPECT_EQ(rate(0.01), "1:2");           // clamped to kMinFrameRate
	EXPECT_EQ(rate(1e6), "1000:1");         // clamped to kMaxFrameRate
	EXPECT_EQ(rate(std::nan("")), "1:2");
}
