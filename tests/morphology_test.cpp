// The mask morphology of the seeding (algo/morphology.hpp, algo/mask_rows.hpp):
// erosion and dilation against brute force on every kernel path, the SSE2
// and NEON rows against the C rows bit for bit, and the component labelling against
// a flood-fill reference.
#include "algo/mask_rows.hpp"
#include "algo/morphology.hpp"
#include "tests/simd_paths.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <iterator>
#include <random>
#include <vector>

using namespace depthkey;

TEST(Morphology, ErodeAndDilateMatchBruteForce)
{
	std::mt19937 rng(2);
	std::bernoulli_distribution on(0.6);
	Gray8Image in(37, 23), out;
	MorphologyScratch scratch;
	for (int trial = 0; trial < 6; ++trial) {
		for (size_t i = 0; i < in.size(); ++i)
			in.data()[i] = on(rng) ? 255 : 0;
		for (int r = 0; r <= 5; ++r)
			for (bool erode : { true, false }) {
				KernelPath path = simd_test::kAllPaths[trial % std::size(simd_test::kAllPaths)];
				(erode ? erodeSquare : dilateSquare)(in, r, out, scratch, path);
				for (int y = 0; y < in.height(); ++y)
					for (int x = 0; x < in.width(); ++x) {
						bool all = true, any = false;
						for (int yy = std::max(0, y - r); yy <= std::min(in.height() - 1, y + r); ++yy)
							for (int xx = std::max(0, x - r); xx <= std::min(in.width() - 1, x + r); ++xx) {
								all = all && in.at(xx, yy);
								any = any || in.at(xx, yy);
							}
						ASSERT_EQ(out.at(x, y), (erode ? all : any) ? 255 : 0) << r << " " << x << "," << y;
					}
			}
	}
}

// The SSE2 and NEON mask rows against the C rows, bit for bit, for odd
// widths and unaligned pointers.
TEST(Morphology, SimdMaskRowsEqualTheCRows)
{
	std::mt19937 rng(4);
	std::uniform_int_distribution<int> byte(0, 255);
	for (int width : { 0, 1, 15, 16, 17, 33, 160, 161 }) {
		for (int offset : { 0, 1, 3 }) {
			std::vector<uint8_t> acc(width + offset), src(width + offset);
			for (int i = 0; i < width + offset; ++i) {
				acc[i] = uint8_t(byte(rng));
				src[i] = uint8_t(byte(rng));
			}
			for (bool erode : { false, true })
				for (KernelPath path : simd_test::kSimdPaths) {
					std::vector<uint8_t> c = acc, simd = acc;
					maskRow(KernelPath::C, erode)(c.data() + offset, src.data() + offset, width);
					maskRow(path, erode)(simd.data() + offset, src.data() + offset, width);
					ASSERT_EQ(c, simd) << simd_test::pathName(path) << " width " << width
							   << " offset " << offset << " erode " << erode;
				}
		}
	}
}

TEST(Morphology, ComponentLabelsMatchAFloodFillReference)
{
	std::mt19937 rng(8);
	std::bernoulli_distribution on(0.5);
	ComponentScratch scratch;
	for (int trial = 0; trial < 20; ++trial) {
		Gray8Image mask(31, 17);
		for (size_t i = 0; i < mask.size(); ++i)
			mask.data()[i] = on(rng) ? 255 : 0;
		// Reference: label by repeated relaxation (min label of 4-neighbours).
		const int w = mask.width(), n = int(mask.size());
		std::vector<int> label(n);
		for (int i = 0; i < n; ++i)
			label[i] = mask.data()[i] ? i : -1;
		for (bool changed = true; changed;) {
			changed = false;
			for (int i = 0; i < n; ++i) {
				if (label[i] < 0)
					continue;
				int x = i % w;
				for (int q : { x > 0 ? i - 1 : -1, x + 1 < w ? i + 1 : -1, i - w, i + w < n ? i + w : -1 })
					if (q >= 0 && label[q] >= 0 && label[q] < label[i]) {
						label[i] = label[q];
						changed = true;
					}
			}
		}
		std::vector<int> size(n, 0);
		for (int l : label)
			if (l >= 0)
				size[l]++;
		int best = -1;
		for (int i = 0; i < n; ++i)
			if (best < 0 || size[i] > size[best])
				best = i;
		// The largest labelled component (the first in raster order on a
		// tie) is the reference's largest, pixel for pixel.
		Gray8Image got = mask;
		const int count = labelComponents(got, scratch);
		int largest = -1;
		for (int k = 0; k < count; ++k)
			if (largest < 0 || scratch.sizes[size_t(k)] > scratch.sizes[size_t(largest)])
				largest = k;
		keepComponent(got, scratch, largest);
		const int kept = largest >= 0 ? scratch.sizes[size_t(largest)] : 0;
		ASSERT_EQ(kept, size[best]);
		for (int i = 0; i < n; ++i)
			ASSERT_EQ(got.data()[i] != 0, label[i] == best) << trial << " " << i;
	}
}
