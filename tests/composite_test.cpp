// The composite kernel in fixed point against the paper's formula in double:
//   composite = board * (1 - o*a) + lecturer * (o*a)
// Tolerance: 1 code value (the Q8 weight rounds to 1/256, the result to 1).
#include "algo/composite.hpp"
#include "tests/simd_paths.hpp"

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

namespace {

// Random rows whose alpha is flat in runs (as a matte is: 0 off the
// lecturer, 255 on it) with soft values between, so both the SSE2 blocks of
// one weight and the mixed blocks are exercised.
struct RandomRows {
	std::vector<Rgb8> lecturer, board;
	std::vector<uint8_t> alpha;

	RandomRows(int width, std::mt19937 &rng)
		: lecturer(width + 1), board(width + 1), alpha(width + 1)
	{
		std::uniform_int_distribution<int> byte(0, 255), run(1, 40), kind(0, 3);
		for (int i = 0; i <= width; ++i) {
			lecturer[i] = { uint8_t(byte(rng)), uint8_t(byte(rng)), uint8_t(byte(rng)) };
			board[i] = { uint8_t(byte(rng)), uint8_t(byte(rng)), uint8_t(byte(rng)) };
		}
		for (int i = 0; i <= width;) {
			int n = run(rng), k = kind(rng);
			uint8_t flat = k == 0 ? 0 : k == 1 ? 255 : uint8_t(byte(rng));
			for (int j = 0; j < n && i <= width; ++j, ++i)
				alpha[i] = k == 3 ? uint8_t(byte(rng)) : flat;
		}
	}
};

} // namespace

// The SSE2 and NEON rows against the C rows, bit for bit, for widths about
// each vector step and a few long ones, at every pointer offset the byte
// arrays allow.
TEST(Composite, SimdRowsEqualTheCRowsBitForBit)
{
	std::mt19937 rng(11);
	size_t compared = 0;
	for (int width : { 0, 1, 2, 3, 15, 16, 17, 18, 19, 31, 33, 47, 64, 100, 641, 1919 }) {
		for (int offset = 0; offset < 2; ++offset) { // offset 1: every pointer off its alignment
			RandomRows rows(width, rng);
			const Rgb8 *l = rows.lecturer.data() + offset, *b = rows.board.data() + offset;
			const uint8_t *a = rows.alpha.data() + offset;
			for (KernelPath path : simd_test::kSimdPaths) {
				for (int opacity : { 0, 77, 128, 256 }) {
					std::vector<Rgb8> outC(width + 1), outSimd(width + 1);
					compositeRow_C(l, a, b, opacity, outC.data() + offset, width);
					compositeRow(path, l, a, b, opacity, outSimd.data() + offset, width);
					ASSERT_EQ(outC, outSimd) << simd_test::pathName(path) << " composite width " << width
								 << " offset " << offset << " opacity " << opacity;
				}
				std::vector<Rgba8> layerC(width + 1), layerSimd(width + 1);
				lecturerLayerRow_C(l, a, layerC.data() + offset, width);
				lecturerLayerRow(path, l, a, layerSimd.data() + offset, width);
				ASSERT_EQ(layerC, layerSimd) << simd_test::pathName(path) << " lecturer layer width " << width
							     << " offset " << offset;
			}
			compared += width;
		}
	}
	EXPECT_GT(compared, 5000u);
}

TEST(Composite, WholeImagesAgreeOnEveryKernelPath)
{
	std::mt19937 rng(5);
	const int w = 97, h = 13;
	RgbImage lecturer(w, h), board(w, h), outC, outBest;
	Gray8Image alpha(w, h);
	for (int y = 0; y < h; ++y) {
		RandomRows rows(w, rng);
		std::copy(rows.lecturer.begin(), rows.lecturer.begin() + w, lecturer.row(y));
		std::copy(rows.board.begin(), rows.board.begin() + w, board.row(y));
		std::copy(rows.alpha.begin(), rows.alpha.begin() + w, alpha.row(y));
	}
	composite(lecturer, alpha, board, 128, outC, KernelPath::C);
	RgbaImage layerC, layerBest;
	lecturerLayer(lecturer, alpha, layerC, KernelPath::C);
	for (KernelPath path : simd_test::kSimdPaths) {
		composite(lecturer, alpha, board, 128, outBest, path);
		EXPECT_EQ(outC, outBest) << simd_test::pathName(path);
		lecturerLayer(lecturer, alpha, layerBest, path);
		EXPECT_EQ(layerC, layerBest) << simd_test::pathName(path);
	}
}

// Where the matte is 0 outside the ROI, blending only the ROI and copying the
// board elsewhere gives the whole-image composite, on every path; an empty
// ROI gives the board.
TEST(Composite, RoiCompositeEqualsTheWholeImageComposite)
{
	std::mt19937 rng(3);
	const int w = 83, h = 21;
	RgbImage lecturer(w, h), board(w, h), whole, part;
	Gray8Image alpha(w, h, 0);
	const Roi roi{ 9, 4, 70, 17 };
	for (int y = 0; y < h; ++y) {
		RandomRows rows(w, rng);
		std::copy(rows.lecturer.begin(), rows.lecturer.begin() + w, lecturer.row(y));
		std::copy(rows.board.begin(), rows.board.begin() + w, board.row(y));
		if (y >= roi.y0 && y < roi.y1)
			std::copy(rows.alpha.begin() + roi.x0, rows.alpha.begin() + roi.x1, alpha.row(y) + roi.x0);
	}
	for (KernelPath path : simd_test::kAllPaths) {
		composite(lecturer, alpha, board, 200, whole, path);
		part = RgbImage(w, h, Rgb8{ 1, 2, 3 }); // stale content must all be overwritten
		compositeRoi(lecturer, alpha, board, roi, 200, part, path);
		EXPECT_EQ(part, whole);
		compositeRoi(lecturer, alpha, board, Roi{}, 200, part, path);
		EXPECT_EQ(part, board);
	}
}

// A solid board as one row (the pipeline's, issue 15) composites as the
// whole board of that colour, inside and outside the ROI.
TEST(Composite, AOneRowBoardStandsForEveryRow)
{
	std::mt19937 rng(4);
	const int w = 83, h = 21;
	const Rgb8 colour{ 30, 60, 40 };
	RgbImage lecturer(w, h), whole, part;
	Gray8Image alpha(w, h, 0);
	const Roi roi{ 9, 4, 70, 17 };
	for (int y = 0; y < h; ++y) {
		RandomRows rows(w, rng);
		std::copy(rows.lecturer.begin(), rows.lecturer.begin() + w, lecturer.row(y));
		if (y >= roi.y0 && y < roi.y1)
			std::copy(rows.alpha.begin() + roi.x0, rows.alpha.begin() + roi.x1, alpha.row(y) + roi.x0);
	}
	for (KernelPath path : simd_test::kAllPaths) {
		compositeRoi(lecturer, alpha, RgbImage(w, h, colour), roi, 200, whole, path);
		part = RgbImage(w, h, Rgb8{ 1, 2, 3 });
		compositeRoi(lecturer, alpha, RgbImage(w, 1, colour), roi, 200, part, path);
		EXPECT_EQ(part, whole);
		compositeRoi(lecturer, alpha, RgbImage(w, 1, colour), Roi{}, 200, part, path);
		EXPECT_EQ(part, RgbImage(w, h, colour));
	}
}
