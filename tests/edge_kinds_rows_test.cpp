// The boundary unmixing's kinds row (algo/edge_kinds_rows.hpp): the C row
// against the kinds' definition, and the SSE2 and NEON rows against the C
// row bit for bit, for mattes of 0 and 255 (what the unmixing sees) and of
// any bytes, runs of every length about the vector steps, unaligned.
#include "algo/edge_kinds_rows.hpp"
#include "tests/simd_paths.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

using namespace depthkey;

TEST(EdgeKindsRows, EveryRowGivesTheKindsOfTheFiveSum)
{
	std::mt19937 rng(31);
	int kindsSeen[4] = {};
	for (bool binary : { true, false })
		for (int n : { 0, 1, 15, 16, 17, 31, 32, 33, 64, 101 })
			for (int offset : { 0, 1, 9 })
				for (int trial = 0; trial < 4; ++trial) {
					// Rows with the neighbours at -1 and n; long runs of one
					// value, so that all five often agree.
					std::vector<uint8_t> rows[3];
					for (auto &row : rows) {
						row.resize(size_t(n + offset + 2));
						uint8_t v = 0;
						for (uint8_t &b : row) {
							if (rng() % 5 == 0)
								v = binary ? uint8_t(255 * (rng() % 2)) : uint8_t(rng());
							b = v;
						}
					}
					const uint8_t *up = rows[0].data() + offset + 1, *m = rows[1].data() + offset + 1;
					const uint8_t *down = rows[2].data() + offset + 1;
					std::vector<uint8_t> want(static_cast<size_t>(n)), got(static_cast<size_t>(n));
					for (int x = 0; x < n; ++x) {
						const int around = m[x] + m[x - 1] + m[x + 1] + up[x] + down[x];
						want[size_t(x)] = around == 1275 ? kEdgeKindLecturerInside
								  : around == 0  ? kEdgeKindBoardInside
								  : m[x]         ? kEdgeKindLecturerEdge
										 : kEdgeKindBoardEdge;
						++kindsSeen[want[size_t(x)]];
					}
					for (KernelPath path : simd_test::kAllPaths) {
						std::fill(got.begin(), got.end(), uint8_t(99));
						edgeKindsRow(path)(up, m, down, n, got.data());
						ASSERT_EQ(got, want) << simd_test::pathName(path) << " n " << n << " offset " << offset
								     << (binary ? " 0/255" : " any bytes");
					}
				}
	for (int kind = 0; kind < 4; ++kind)
		EXPECT_GT(kindsSeen[kind], 100) << "kind " << kind;
}
