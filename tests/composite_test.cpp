// The composite kernel in fixed point against the paper's formula in double:
//   composite = board * (1 - o*a) + lecturer * (o*a)
// Tolerance: 1 code value (the Q8 weight rounds to 1/256, the result to 1).
#include "algo/composite.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

using namespace depthkey;

TEST(Composite, FixedPointMatchesFloatReferenceWithinOneCodeValue)
{
	std::mt19937 rng(7);
	std::uniform_int_distribution<int> byte(0, 255);
	const int width = 4096;
	std::vector<Rgb8> lecturer(width), board(width), out(width);
	std::vector<uint8_t> alpha(width);
	int histogram[3] = {};
	for (double opacity : { 0.0, 0.25, 0.5, 0.73, 1.0 }) {
		for (int i = 0; i < width; ++i) {
			lecturer[i] = { uint8_t(byte(rng)), uint8_t(byte(rng)), uint8_t(byte(rng)) };
			board[i] = { uint8_t(byte(rng)), uint8_t(byte(rng)), uint8_t(byte(rng)) };
			alpha[i] = uint8_t(i < 256 ? i : byte(rng)); // every alpha value at least once
		}
		int q8 = opacityToQ8(opacity);
		compositeRow_C(lecturer.data(), alpha.data(), board.data(), q8, out.data(), width);
		for (int i = 0; i < width; ++i) {
			double w = opacity * alpha[i] / 255.0;
			auto check = [&](uint8_t l, uint8_t b, uint8_t o) {
				double ref = b * (1.0 - w) + l * w;
				int err = static_cast<int>(std::lround(std::fabs(o - ref)));
				ASSERT_LE(std::fabs(o - ref), 1.0) << "opacity " << opacity << " alpha " << int(alpha[i]);
				histogram[std::min(err, 2)]++;
			};
			check(lecturer[i].r, board[i].r, out[i].r);
			check(lecturer[i].g, board[i].g, out[i].g);
			check(lecturer[i].b, board[i].b, out[i].b);
		}
	}
	std::printf("composite |error| histogram: 0:%d 1:%d >1:%d\n", histogram[0], histogram[1], histogram[2]);
}

TEST(Composite, EndpointsAreExact)
{
	Rgb8 lecturer{ 200, 100, 50 }, board{ 10, 20, 30 }, out;
	uint8_t opaque = 255, clear = 0;
	compositeRow_C(&lecturer, &opaque, &board, 256, &out, 1);
	EXPECT_EQ(out, lecturer);
	compositeRow_C(&lecturer, &clear, &board, 256, &out, 1);
	EXPECT_EQ(out, board);
	compositeRow_C(&lecturer, &opaque, &board, 0, &out, 1);
	EXPECT_EQ(out, board);
}

TEST(Composite, LecturerLayerIsStraightAlpha)
{
	RgbImage colour(3, 1, Rgb8{ 9, 8, 7 });
	Gray8Image alpha(3, 1);
	alpha.at(1, 0) = 128;
	RgbaImage out;
	lecturerLayer(colour, alpha, out);
	EXPECT_EQ(out.at(0, 0), (Rgba8{ 9, 8, 7, 0 }));
	EXPECT_EQ(out.at(1, 0), (Rgba8{ 9, 8, 7, 128 }));
}

TEST(Composite, OpacityToQ8ClampsAndRounds)
{
	EXPECT_EQ(opacityToQ8(-1.0), 0);
	EXPECT_EQ(opacityToQ8(0.5), 128);
	EXPECT_EQ(opacityToQ8(1.0), 256);
	EXPECT_EQ(opacityToQ8(2.0), 256);
	EXPECT_EQ(opacityToQ8(std::nan("")), 0);
}
