// The seed mapper's max-painting rows (algo/max_paint_rows.hpp): the SSE2 and
// NEON rows paint the C row's bytes, bit for bit, for every length about the
// vector steps, every room (down to none beyond n), unaligned pointers and
// random contents, and leave every byte outside [0, n) as it was; the C row
// against a plain loop.
#include "algo/max_paint_rows.hpp"
#include "tests/simd_paths.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

using namespace depthkey;

TEST(MaxPaintRows, EveryRowPaintsTheMaxOfTheFirstNBytesOnly)
{
	std::mt19937 rng(28);
	size_t checks = 0;
	for (int n = 0; n <= 40; ++n)
		for (int extra : { 0, 1, 5, 15, 16, 30 })
			for (int offset : { 0, 1, 7 }) {
				// A guard byte either side of the row's room shows a stray write.
				const int room = n + extra, size = offset + room + 2;
				std::vector<uint8_t> before(static_cast<size_t>(size));
				for (uint8_t &v : before)
					v = uint8_t(rng());
				const uint8_t value = uint8_t(rng());
				std::vector<uint8_t> want = before;
				for (int x = 0; x < n; ++x)
					want[size_t(offset + 1 + x)] = std::max(want[size_t(offset + 1 + x)], value);
				std::vector<uint8_t> c = before;
				maxPaintRow_C(c.data() + offset + 1, n, room, value);
				ASSERT_EQ(c, want) << "C n " << n << " room " << room;
				for (KernelPath path : simd_test::kSimdPaths) {
					std::vector<uint8_t> simd = before;
					maxPaintRow(path)(simd.data() + offset + 1, n, room, value);
					ASSERT_EQ(simd, c) << simd_test::pathName(path) << " n " << n << " room " << room
							   << " offset " << offset;
				}
				++checks;
			}
	EXPECT_EQ(checks, 41u * 6u * 3u);
}

TEST(MaxPaintRows, ExtremeValuesPaintAsTheCRow)
{
	// 0 paints nothing, 255 everything, whatever the row holds.
	for (uint8_t value : { uint8_t(0), uint8_t(255) })
		for (KernelPath path : simd_test::kSimdPaths) {
			std::vector<uint8_t> row(48), c(48);
			for (size_t i = 0; i < row.size(); ++i)
				row[i] = c[i] = uint8_t(i * 37);
			maxPaintRow(path)(row.data() + 3, 13, 45, value);
			maxPaintRow_C(c.data() + 3, 13, 45, value);
			EXPECT_EQ(row, c) << simd_test::pathName(path) << " value " << int(value);
		}
}
