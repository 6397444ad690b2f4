// The SIOX band scan (algo/band_scan.hpp): the SSE2 and NEON rows give the C
// row's x, bit for bit, for rows of seeds with undecided labels at every
// position of a 16-label block (and none), every start and end about the
// vector steps, and unaligned pointers; and the C row against a plain loop.
#include "algo/band_scan.hpp"
#include "tests/simd_paths.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

using namespace depthkey;

namespace {

// The reference, written apart from the C row: the first non-seed label.
int firstNonSeed(const std::vector<uint8_t> &labels, int x, int end)
{
	for (; x < end; ++x)
		if (labels[x] != kTrimapBoard && labels[x] != kTrimapLecturer)
			return x;
	return end;
}

} // namespace

TEST(BandScan, EveryRowFindsTheFirstNonSeed)
{
	std::mt19937 rng(15);
	const uint8_t seeds[] = { kTrimapBoard, kTrimapLecturer };
	// Not seeds: every other trimap label, and bytes next to the seeds' values.
	const uint8_t others[] = { kTrimapUndecided, kTrimapSubset, kTrimapInRange, 1, 254, 127 };
	size_t checks = 0, found = 0;
	for (int length : { 0, 1, 15, 16, 17, 31, 32, 33, 50, 64, 101 })
		for (int offset : { 0, 1, 7 })
			for (int undecidedAt = -1; undecidedAt < length; ++undecidedAt) {
				std::vector<uint8_t> row(size_t(length + offset));
				for (uint8_t &v : row)
					v = seeds[rng() % 2];
				if (undecidedAt >= 0)
					row[size_t(offset + undecidedAt)] = others[rng() % 6];
				// A second non-seed further on must not be the one found.
				if (undecidedAt >= 0 && undecidedAt + 5 < length)
					row[size_t(offset + undecidedAt + 5)] = kTrimapUndecided;
				for (int start : { 0, 1, 16 }) {
					if (start > length)
						continue;
					const int want = firstNonSeed(row, offset + start, offset + length) - offset;
					const int c = nextUndecidedRow_C(row.data() + offset, start, length);
					ASSERT_EQ(c, want) << "C length " << length << " at " << undecidedAt << " start " << start;
					for (KernelPath path : simd_test::kSimdPaths)
						ASSERT_EQ(bandScanRow(path)(row.data() + offset, start, length), c)
							<< simd_test::pathName(path) << " length " << length << " offset " << offset
							<< " at " << undecidedAt << " start " << start;
					++checks;
					found += c < length;
				}
			}
	EXPECT_GT(checks, 2000u);
	EXPECT_GT(found, 1000u); // most rows had a non-seed to find
}

TEST(BandScan, EachPathHasItsOwnRow)
{
	EXPECT_EQ(bandScanRow(KernelPath::C), &nextUndecidedRow_C);
	EXPECT_EQ(bandScanRow(KernelPath::Sse2), &nextUndecidedRow_SSE2);
	EXPECT_EQ(bandScanRow(KernelPath::Neon), &nextUndecidedRow_NEON);
}
