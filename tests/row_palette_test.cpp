// The simulator's row-by-row palettes (hal/sim/row_palette.hpp): every row
// read back bit for bit, whether it keeps a palette or its values whole.
#include "hal/sim/row_palette.hpp"
#include "hal/sim/hash_noise.hpp"

#include <bit>
#include <gtest/gtest.h>
#include <limits>

using depthkey::sim::RowPalette;
using depthkey::sim::mixHash;

TEST(RowPalette, RowsReadBackBitForBit)
{
	const int width = 300, height = 7;
	std::vector<float> z(size_t(width) * height);
	for (int j = 0; j < height; ++j)
		for (int i = 0; i < width; ++i) {
			float &v = z[size_t(j) * width + i];
			uint64_t h = mixHash(uint64_t(j) * width + i);
			switch (j) {
			case 0: v = 2.0f; break;                                          // one value
			case 1: v = 1.0f + float(i % 256) / 1024; break;                  // 256: a full palette
			case 2: v = 1.0f + float(i) / 1024; break;                        // 300: kept whole
			case 3: v = i % 2 ? 0.0f : -0.0f; break;                          // equal, not the same bits
			case 4: v = i % 3 ? std::numeric_limits<float>::max() : 1.25f; break; // nothing hit
			default: v = std::bit_cast<float>(uint32_t(h)); break;           // any bits, NaNs too
			}
		}
	RowPalette<float> depth;
	depth.assign(width, height, z);
	// Out of order and twice, as a caller may ask.
	for (int j : { 3, 0, 6, 1, 1, 2, 5, 4, 0 }) {
		const float *row = depth.row(j);
		for (int i = 0; i < width; ++i)
			ASSERT_EQ(std::bit_cast<uint32_t>(row[i]), std::bit_cast<uint32_t>(z[size_t(j) * width + i]))
				<< "row " << j << " sample " << i;
	}
}
