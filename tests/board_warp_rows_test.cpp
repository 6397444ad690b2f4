// The SSE2, SSSE3, AVX2 and NEON rows of the board warp give the C row's bytes, for random
// sources, fractions (0 and 255 included), unseen pixels, zero and full
// alpha, and every opacity class; for every count up to a few groups of four
// and a long odd one, at every start offset (unaligned map, layer and
// composite pointers), with groups where nobody is or one pixel is unseen
// (the C pixel), every pixel of the row written and none outside it.
#include "algo/board_warp_rows.hpp"
#include "tests/simd_paths.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

using namespace depthkey;

TEST(BoardWarpRows, SimdRowsMatchC)
{
	constexpr int kW = 37, kH = 9, kMaxCount = 211, kMaxOffset = 3;
	constexpr int kLen = kMaxCount + kMaxOffset + 1; // a guard pixel after the row
	std::mt19937 rng(42);
	std::uniform_int_distribution<int> byte(0, 255);
	std::vector<Rgba8> source(size_t(kW) * kH);
	for (Rgba8 &p : source) {
		int a = byte(rng);
		p = { uint8_t(byte(rng)), uint8_t(byte(rng)), uint8_t(byte(rng)), uint8_t(a < 80 ? 0 : a > 180 ? 255 : a) };
	}
	// The left half of the top rows transparent, colour kept: groups of
	// four with nobody, and mixed ones, whose colour must not leak.
	for (int y = 0; y < 4; ++y)
		for (int x = 0; x < 14; ++x)
			source[size_t(y) * kW + x].a = 0;
	std::vector<int32_t> index(kLen);
	std::vector<uint16_t> frac(kLen);
	std::vector<Rgb8> board(kLen);
	for (int x = 0; x < kLen; ++x) {
		const bool nobody = (x / 8) % 3 == 1; // runs of 8: aligned or not, whole groups
		int sx = byte(rng) % (nobody ? 12 : kW - 1), sy = byte(rng) % (nobody ? 3 : kH - 1);
		index[x] = x % 17 == 0 ? kOutsideView : sy * kW + sx;
		int fx = x % 11 == 0 ? 0 : x % 13 == 0 ? 255 : byte(rng);
		int fy = x % 7 == 0 ? 0 : x % 5 == 0 ? 255 : byte(rng);
		frac[x] = uint16_t(fx | fy << 8);
		board[x] = { uint8_t(byte(rng)), uint8_t(byte(rng)), uint8_t(byte(rng)) };
	}
	std::vector<int> counts{ kMaxCount };
	for (int c = 0; c <= 25; ++c)
		counts.push_back(c);
	for (KernelPath path : simd_test::kSimdPaths)
		for (int opacity : { 0, 1, 128, 255, 256 })
			for (int count : counts)
				for (int offset = 0; offset <= kMaxOffset; ++offset) {
					// Outputs start as garbage: every pixel of the row is written,
					// none outside it.
					const Rgb8 was{ 7, 77, 177 };
					const Rgba8 wasLayer{ 5, 55, 155, 255 };
					std::vector<Rgb8> cComposite(kLen, was), sComposite = cComposite;
					std::vector<Rgba8> cLayer(kLen, wasLayer), sLayer = cLayer;
					BoardWarpRow c{ index.data() + offset, frac.data() + offset, source.data(), kW, board.data() + offset,
							cComposite.data() + offset, cLayer.data() + offset, count };
					BoardWarpRow s = c;
					s.composite = sComposite.data() + offset;
					s.layer = sLayer.data() + offset;
					boardWarpRow_C(c, opacity);
					boardWarpRow(path, s, opacity);
					size_t lit = 0;
					for (int x = 0; x < kLen; ++x) {
						const bool inRow = x >= offset && x < offset + count;
						ASSERT_EQ(cComposite[x], sComposite[x]) << simd_test::pathName(path) << " x " << x << " opacity " << opacity << " count " << count;
						ASSERT_EQ(cLayer[x], sLayer[x]) << simd_test::pathName(path) << " x " << x << " opacity " << opacity << " count " << count;
						if (!inRow) {
							ASSERT_EQ(sComposite[x], was) << "written outside the row: x " << x;
							ASSERT_EQ(sLayer[x], wasLayer) << "written outside the row: x " << x;
						}
						if (inRow && cLayer[x].a == 0) {
							ASSERT_EQ(cLayer[x], (Rgba8{ 0, 0, 0, 0 })) << "a transparent pixel has no colour: x " << x;
						}
						lit += cLayer[x].a > 0;
					}
					if (count == kMaxCount) {
						EXPECT_GT(lit, size_t(count / 3)); // many samples touch the lecturer
					}
				}
}

// Where nobody is (unseen, or no alpha in the four taps) the row gives the
// board and a transparent layer, the source's colour dropped.
TEST(BoardWarpRows, NobodyIsTheBoardAndTransparent)
{
	std::vector<Rgba8> source(4 * 3, Rgba8{ 9, 8, 7, 0 });
	std::vector<int32_t> index{ kOutsideView, 0, 1, 2, 4, 5, 6, kOutsideView, 0 };
	std::vector<uint16_t> frac(index.size(), uint16_t(100 | 100 << 8));
	const std::vector<Rgb8> board(index.size(), Rgb8{ 1, 2, 3 });
	for (KernelPath path : simd_test::kAllPaths) {
		std::vector<Rgb8> composite(index.size(), Rgb8{ 4, 5, 6 });
		std::vector<Rgba8> layer(index.size(), Rgba8{ 1, 1, 1, 1 });
		boardWarpRow(path, { index.data(), frac.data(), source.data(), 4, board.data(), composite.data(), layer.data(), int(index.size()) }, 256);
		for (size_t x = 0; x < index.size(); ++x) {
			EXPECT_EQ(composite[x], (Rgb8{ 1, 2, 3 })) << x;
			EXPECT_EQ(layer[x], (Rgba8{ 0, 0, 0, 0 })) << x;
		}
	}
}

// Each path runs its own row where this CPU has the instructions (else the
// comparisons above would hold trivially).
TEST(BoardWarpRows, EachPathRunsItsOwnRow)
{
	EXPECT_EQ(boardWarpRowFn(KernelPath::C), &boardWarpRow_C);
	EXPECT_EQ(boardWarpRowFn(KernelPath::Sse2), &boardWarpRow_SSE2);
	EXPECT_EQ(boardWarpRowFn(KernelPath::Ssse3), cpuHasSsse3() ? &boardWarpRow_SSSE3 : &boardWarpRow_SSE2);
	EXPECT_EQ(boardWarpRowFn(KernelPath::Avx2), cpuHasAvx2()    ? &boardWarpRow_AVX2
						    : cpuHasSsse3() ? &boardWarpRow_SSSE3
								    : &boardWarpRow_SSE2);
	EXPECT_EQ(boardWarpRowFn(KernelPath::Neon), &boardWarpRow_NEON);
}
