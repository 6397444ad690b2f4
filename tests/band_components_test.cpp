// BandComponents (algo/band_components.hpp) against the pixel floods it
// replaced in SioxRefiner, kept here as the reference: on random masks of
// seeds and band decisions, blobs and noise, every size of region against
// minKeep, the border counted or not, the result is the same byte for byte.
#include "algo/band_components.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

using namespace depthkey;

namespace {

// --- The reference: SioxRefiner's steps 3 and 4 before issue 28 ---------
constexpr uint8_t kUnreachedLecturer = 1, kUnreachedBoard = 2, kCounting = 4;

void flood(uint8_t *m, int stride, int32_t *stack, size_t top, uint8_t from, uint8_t to)
{
	while (top) {
		const int p = stack[--top];
		auto visit = [&](int q) {
			if (m[q] == from) {
				m[q] = to;
				stack[top++] = q;
			}
		};
		visit(p - 1);
		visit(p + 1);
		visit(p - stride);
		visit(p + stride);
	}
}

template<typename F>
void forEachBandPixel(const std::vector<BandSpan> &spans, int stride, F f)
{
	for (const BandSpan &s : spans)
		for (int x = s.x0, p = (s.y + 1) * stride + s.x0 + 1, k = s.first; x < s.x1; ++x, ++p, ++k)
			f(p, k);
}

void referenceKeep(uint8_t *m, int stride, const std::vector<BandSpan> &spans, size_t bandPixels, bool beyond,
		   size_t minKeep)
{
	std::vector<int32_t> stack(bandPixels);
	forEachBandPixel(spans, stride, [&](int p, int) {
		if (m[p])
			m[p] = kUnreachedLecturer;
	});
	size_t top = 0;
	forEachBandPixel(spans, stride, [&](int p, int) {
		auto anchor = [&](uint8_t n) { return n == 255 || (n == kBandOutside && beyond); };
		if (m[p] == kUnreachedLecturer &&
		    (anchor(m[p - 1]) || anchor(m[p + 1]) || anchor(m[p - stride]) || anchor(m[p + stride]))) {
			m[p] = 255;
			stack[top++] = p;
		}
	});
	flood(m, stride, stack.data(), top, kUnreachedLecturer, 255);
	forEachBandPixel(spans, stride, [&](int p, int) {
		if (m[p] != kUnreachedLecturer)
			return;
		size_t head = 0, tail = 0;
		m[p] = kCounting;
		stack[tail++] = p;
		while (head < tail) {
			const int q = stack[head++];
			for (int r : { q - 1, q + 1, q - stride, q + stride })
				if (m[r] == kUnreachedLecturer) {
					m[r] = kCounting;
					stack[tail++] = r;
				}
		}
		const uint8_t keep = tail >= minKeep ? 255 : 0;
		for (size_t k = 0; k < tail; ++k)
			m[stack[k]] = keep;
	});
}

void referenceFill(uint8_t *m, int stride, const std::vector<BandSpan> &spans, size_t bandPixels,
		   const uint8_t *confidence, uint8_t clearlyBoard)
{
	std::vector<int32_t> stack(bandPixels);
	forEachBandPixel(spans, stride, [&](int p, int) {
		if (!m[p])
			m[p] = kUnreachedBoard;
	});
	auto open = [](uint8_t v) { return v == 0 || v == kBandOutside; };
	size_t top = 0;
	forEachBandPixel(spans, stride, [&](int p, int) {
		if (m[p] == kUnreachedBoard &&
		    (open(m[p - 1]) || open(m[p + 1]) || open(m[p - stride]) || open(m[p + stride]))) {
			m[p] = 0;
			stack[top++] = p;
		}
	});
	flood(m, stride, stack.data(), top, kUnreachedBoard, 0);
	forEachBandPixel(spans, stride, [&](int p, int k) {
		if (m[p] == kUnreachedBoard)
			m[p] = confidence[k] < clearlyBoard ? 0 : 255;
	});
}

// --- Random cases -----------------------------------------------------------
struct Case {
	int w = 0, h = 0, stride = 0;
	std::vector<uint8_t> mask; // (w+2) x (h+2), framed
	std::vector<BandSpan> spans;
	std::vector<uint8_t> confidence;
	size_t bandPixels = 0;
};

// Seeds of either kind in blobs, a band around and between them, band
// decisions in blobs of their own plus single flipped pixels.
Case randomCase(std::mt19937 &rng)
{
	Case c;
	c.w = int(rng() % 60) + 1;
	c.h = int(rng() % 40) + 1;
	c.stride = c.w + 2;
	c.mask.assign(size_t(c.stride) * size_t(c.h + 2), kBandOutside);
	auto blobs = [&](int count, int maxR) {
		std::vector<int> field(size_t(c.w) * size_t(c.h), 0);
		for (int b = 0; b < count; ++b) {
			const int cx = int(rng() % unsigned(c.w)), cy = int(rng() % unsigned(c.h));
			const int r = int(rng() % unsigned(maxR)) + 1, v = int(rng() % 2) + 1;
			for (int y = std::max(0, cy - r); y < std::min(c.h, cy + r + 1); ++y)
				for (int x = std::max(0, cx - r); x < std::min(c.w, cx + r + 1); ++x)
					if ((x - cx) * (x - cx) + (y - cy) * (y - cy) <= r * r)
						field[size_t(y) * size_t(c.w) + size_t(x)] = v;
		}
		return field;
	};
	const std::vector<int> seeds = blobs(int(rng() % 6), 8);     // 0 band, 1 board, 2 lecturer
	const std::vector<int> decided = blobs(int(rng() % 10), 10); // 2: the band says lecturer
	const unsigned bandShare = rng() % 100, noise = rng() % 20;
	for (int y = 0; y < c.h; ++y) {
		for (int x = 0; x < c.w;) {
			auto isBand = [&](int xx) {
				const int s = seeds[size_t(y) * size_t(c.w) + size_t(xx)];
				return s == 0 && (rng() % 100) < bandShare + 1;
			};
			uint8_t *row = c.mask.data() + size_t(y + 1) * size_t(c.stride) + 1;
			if (!isBand(x)) {
				row[x] = seeds[size_t(y) * size_t(c.w) + size_t(x)] == 2 ? 255 : 0;
				++x;
				continue;
			}
			BandSpan span{ y, x, x, int(c.bandPixels) };
			do {
				const bool lecturer = (decided[size_t(y) * size_t(c.w) + size_t(x)] == 2) != (rng() % 100 < noise);
				row[x] = lecturer ? 255 : 0;
				c.confidence.push_back(uint8_t(rng()));
				++x;
				++c.bandPixels;
			} while (x < c.w && seeds[size_t(y) * size_t(c.w) + size_t(x)] == 0);
			span.x1 = x;
			c.spans.push_back(span);
		}
	}
	return c;
}

TEST(BandComponents, SameAsThePixelFloodsOnRandomMasks)
{
	std::mt19937 rng(28);
	BandComponents components;
	size_t changedByKeep = 0, changedByFill = 0;
	for (int i = 0; i < 3000; ++i) {
		Case c = randomCase(rng);
		const bool beyond = rng() % 2;
		const size_t minKeep = rng() % 40 + 1;
		const uint8_t clearlyBoard = uint8_t(rng() % 64);
		std::vector<uint8_t> expected = c.mask, actual = c.mask;
		components.reserve(c.bandPixels);

		referenceKeep(expected.data(), c.stride, c.spans, c.bandPixels, beyond, minKeep);
		components.keepTouchingLecturer(actual.data(), c.stride, c.spans, beyond, minKeep);
		ASSERT_EQ(actual, expected) << "keepTouchingLecturer, case " << i;
		changedByKeep += expected != c.mask;

		const std::vector<uint8_t> kept = expected;
		referenceFill(expected.data(), c.stride, c.spans, c.bandPixels, c.confidence.data(), clearlyBoard);
		components.fillHoles(actual.data(), c.stride, c.spans, c.confidence.data(), clearlyBoard);
		ASSERT_EQ(actual, expected) << "fillHoles, case " << i;
		changedByFill += expected != kept;
	}
	// The cases exercise both steps (each changed a good share of masks).
	EXPECT_GT(changedByKeep, 300u);
	EXPECT_GT(changedByFill, 300u);
}

TEST(BandComponents, ARegionJoinedOnlyThroughTheRowBelowIsOneRegion)
{
	// A U of band lecturer pixels: its left arm touches a lecturer seed, its
	// right arm only through the bottom row. The whole U stays.
	//   row 0: S L . L       (S seed 255, L band lecturer, . band board)
	//   row 1: . L L L
	const int w = 4, h = 2, stride = w + 2;
	std::vector<uint8_t> mask(size_t(stride) * (h + 2), kBandOutside);
	auto px = [&](int x, int y) -> uint8_t & { return mask[size_t(y + 1) * stride + size_t(x) + 1]; };
	px(0, 0) = 255;
	px(1, 0) = 255, px(2, 0) = 0, px(3, 0) = 255;
	px(0, 1) = 0, px(1, 1) = 255, px(2, 1) = 255, px(3, 1) = 255;
	std::vector<BandSpan> spans{ { 0, 1, 4, 0 }, { 1, 0, 4, 3 } };
	BandComponents components;
	components.reserve(7);
	components.keepTouchingLecturer(mask.data(), stride, spans, false, 100);
	EXPECT_EQ(px(3, 0), 255) << "the right arm is joined through row 1";
	EXPECT_EQ(px(2, 1), 255);
	EXPECT_EQ(px(0, 1), 0);
}

} // namespace
