// The SSE2 row of the board warp gives the C row's bytes, for random
// sources, fractions (0 and 255 included), unseen pixels, zero and full
// alpha, and every opacity class.
#include "algo/board_warp_rows.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

using namespace depthkey;

TEST(BoardWarpRows, Sse2MatchesC)
{
	constexpr int kW = 37, kH = 9, kCount = 211;
	std::mt19937 rng(42);
	std::uniform_int_distribution<int> byte(0, 255);
	std::vector<Rgba8> source(size_t(kW) * kH);
	for (Rgba8 &p : source) {
		int a = byte(rng);
		p = { uint8_t(byte(rng)), uint8_t(byte(rng)), uint8_t(byte(rng)), uint8_t(a < 80 ? 0 : a > 180 ? 255 : a) };
	}
	std::vector<int32_t> index(kCount);
	std::vector<uint16_t> frac(kCount);
	std::vector<Rgb8> board(kCount);
	for (int x = 0; x < kCount; ++x) {
		int sx = byte(rng) % (kW - 1), sy = byte(rng) % (kH - 1);
		index[x] = x % 17 == 0 ? kOutsideView : sy * kW + sx;
		int fx = x % 11 == 0 ? 0 : x % 13 == 0 ? 255 : byte(rng);
		int fy = x % 7 == 0 ? 0 : x % 5 == 0 ? 255 : byte(rng);
		frac[x] = uint16_t(fx | fy << 8);
		board[x] = { uint8_t(byte(rng)), uint8_t(byte(rng)), uint8_t(byte(rng)) };
	}
	for (int opacity : { 0, 1, 128, 255, 256 }) {
		std::vector<Rgb8> cComposite(kCount), sComposite(kCount);
		std::vector<Rgba8> cLayer(kCount), sLayer(kCount);
		BoardWarpRow c{ index.data(), frac.data(), source.data(), kW, board.data(), cComposite.data(), cLayer.data(), kCount };
		BoardWarpRow s = c;
		s.composite = sComposite.data();
		s.layer = sLayer.data();
		boardWarpRow_C(c, opacity);
		boardWarpRow_SSE2(s, opacity);
		size_t lit = 0;
		for (int x = 0; x < kCount; ++x) {
			ASSERT_EQ(cComposite[x], sComposite[x]) << "x " << x << " opacity " << opacity;
			ASSERT_EQ(cLayer[x].r, sLayer[x].r) << x;
			ASSERT_EQ(cLayer[x].g, sLayer[x].g) << x;
			ASSERT_EQ(cLayer[x].b, sLayer[x].b) << x;
			ASSERT_EQ(cLayer[x].a, sLayer[x].a) << x;
			lit += cLayer[x].a > 0;
		}
		EXPECT_GT(lit, size_t(kCount / 2)); // most samples touch the lecturer
	}
}
