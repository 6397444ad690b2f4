// The column sums' row kernels (algo/column_sums_rows.hpp): the C rows
// against plain loops that add the row coming in and take off the row
// going out one sum at a time, as ColumnSums::bring does; the SSE2 and
// NEON rows against the C rows bit for bit, for runs of every length about
// the vector steps, unaligned pointers, wrapped sums and every value.
#include "algo/column_sums_rows.hpp"
#include "tests/simd_paths.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

using namespace depthkey;

namespace {

constexpr int kLengths[] = { 0, 1, 3, 4, 7, 8, 9, 15, 16, 17, 33, 100 };

// Column sums to start from: anything, wrapped ones too.
std::vector<uint32_t> startingSums(std::mt19937 &rng, size_t n)
{
	std::vector<uint32_t> s(n);
	for (uint32_t &v : s)
		v = rng();
	return s;
}

std::vector<uint8_t> bytes(std::mt19937 &rng, size_t n)
{
	std::vector<uint8_t> v(n);
	for (uint8_t &b : v)
		b = uint8_t(rng() % 4 == 0 ? 255 * (rng() % 2) : rng()); // the extremes often
	return v;
}

} // namespace

TEST(ColumnSumsRows, MomentRowsMatchTheColumnByColumnSums)
{
	std::mt19937 rng(28);
	size_t checks = 0;
	for (int n : kLengths)
		for (int offset : { 0, 1, 5 }) {
			const size_t size = size_t(n + offset);
			const auto iIn = bytes(rng, size), pIn = bytes(rng, size), iOut = bytes(rng, size), pOut = bytes(rng, size);
			std::array<std::vector<uint32_t>, 4> start;
			for (auto &s : start)
				s = startingSums(rng, size);
			// The reference: in, then out, as bring() does it.
			auto want = start;
			for (int x = offset; x < offset + n; ++x) {
				const uint32_t i = iIn[size_t(x)], p = pIn[size_t(x)], io = iOut[size_t(x)], po = pOut[size_t(x)];
				want[0][size_t(x)] = want[0][size_t(x)] + i - io;
				want[1][size_t(x)] = want[1][size_t(x)] + p - po;
				want[2][size_t(x)] = want[2][size_t(x)] + i * i - io * io;
				want[3][size_t(x)] = want[3][size_t(x)] + i * p - io * po;
			}
			for (KernelPath path : simd_test::kAllPaths) {
				auto got = start;
				momentColumnsRow(path)(iIn.data() + offset, pIn.data() + offset, iOut.data() + offset,
						       pOut.data() + offset, n,
						       { got[0].data() + offset, got[1].data() + offset, got[2].data() + offset,
							 got[3].data() + offset });
				ASSERT_EQ(got, want) << simd_test::pathName(path) << " n " << n << " offset " << offset;
				++checks;
			}
		}
	EXPECT_GT(checks, 150u);
}

TEST(ColumnSumsRows, PairRowsMatchTheColumnByColumnSums)
{
	std::mt19937 rng(29);
	for (int n : kLengths)
		for (int offset : { 0, 1, 3 }) {
			const size_t size = size_t(n + offset);
			std::vector<int32_t> aIn(size), bIn(size), aOut(size), bOut(size);
			for (auto *v : { &aIn, &bIn, &aOut, &bOut })
				for (int32_t &x : *v)
					x = int32_t(rng()); // negative, and far apart
			auto start = std::array{ startingSums(rng, size), startingSums(rng, size) };
			auto want = start;
			for (int x = offset; x < offset + n; ++x) {
				want[0][size_t(x)] = want[0][size_t(x)] + uint32_t(aIn[size_t(x)]) - uint32_t(aOut[size_t(x)]);
				want[1][size_t(x)] = want[1][size_t(x)] + uint32_t(bIn[size_t(x)]) - uint32_t(bOut[size_t(x)]);
			}
			for (KernelPath path : simd_test::kAllPaths) {
				auto got = start;
				pairColumnsRow(path)(aIn.data() + offset, bIn.data() + offset, aOut.data() + offset,
						     bOut.data() + offset, n, { got[0].data() + offset, got[1].data() + offset });
				ASSERT_EQ(got, want) << simd_test::pathName(path) << " n " << n << " offset " << offset;
			}
		}
}

TEST(ColumnSumsRows, SideRowsMatchTheColumnByColumnSums)
{
	std::mt19937 rng(30);
	const SideKinds kinds{ 2, 3 };
	size_t sided = 0;
	for (int n : kLengths)
		for (int offset : { 0, 1, 6 }) {
			const size_t size = size_t(n + offset);
			std::vector<uint8_t> kIn(size), kOut(size);
			for (auto *k : { &kIn, &kOut })
				for (uint8_t &v : *k)
					v = uint8_t(rng() % 6 == 5 ? 255 : rng() % 5); // the kinds, and a byte of none
			auto colours = [&] {
				std::vector<Rgb8> c(size);
				const auto b = bytes(rng, 3 * size);
				for (size_t i = 0; i < size; ++i)
					c[i] = { b[3 * i], b[3 * i + 1], b[3 * i + 2] };
				return c;
			};
			const auto cIn = colours(), cOut = colours();
			std::array<std::vector<uint32_t>, 8> start;
			for (auto &s : start)
				s = startingSums(rng, size);
			auto want = start;
			for (int x = offset; x < offset + n; ++x) {
				const size_t i = size_t(x);
				for (int side = 0; side < 2; ++side) {
					const uint8_t kind = side ? kinds.board : kinds.lecturer;
					auto add = [&](const Rgb8 &c, uint32_t sign) {
						const uint32_t values[4] = { c.r, c.g, c.b, 1 };
						for (size_t k = 0; k < 4; ++k)
							want[size_t(4 * side) + k][i] += sign * values[k];
					};
					if (kIn[i] == kind)
						add(cIn[i], 1u);
					if (kOut[i] == kind)
						add(cOut[i], ~0u);
					sided += kIn[i] == kind;
				}
			}
			for (KernelPath path : simd_test::kAllPaths) {
				auto got = start;
				SideSums sums;
				for (size_t k = 0; k < sums.size(); ++k)
					sums[k] = got[k].data() + offset;
				sideColumnsRow(path)(kIn.data() + offset, cIn.data() + offset, kOut.data() + offset,
						     cOut.data() + offset, n, kinds, sums);
				ASSERT_EQ(got, want) << simd_test::pathName(path) << " n " << n << " offset " << offset;
			}
		}
	EXPECT_GT(sided, 100u);
}
