// The board model's learning rows (algo/board_learn_rows.hpp): the SSE2 and
// NEON rows against the C rows bit for bit (model bytes, visit counts,
// sums, select bytes) on rows of every width 1..67 at odd offsets, with
// pixels never seen, saturated visit counts and extreme colours; and the
// whole BoardModel::learn() / learnDecided() on every path against the
// scalar loops they replaced, kept here as the reference.
#include "algo/board_learn_rows.hpp"
#include "algo/board_model.hpp"
#include "algo/trimap.hpp"
#include "tests/simd_paths.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

using namespace depthkey;

namespace {

// 0, 255 or anything, each a third of the time: the extremes where a step
// or a saturating count would wrap.
uint8_t extremeByte(std::mt19937 &rng)
{
	const unsigned kind = rng() % 3;
	return kind == 0 ? 0 : kind == 1 ? 255 : uint8_t(rng());
}

// Trimap bytes in runs (regions and the lecturer's silhouette), every class.
uint8_t trimapByte(std::mt19937 &rng)
{
	const uint8_t kinds[] = { kTrimapBoard, kTrimapBoard, kTrimapUndecided, kTrimapLecturer,
				  kTrimapSubset, kTrimapInRange, 1, 254 };
	return kinds[rng() % std::size(kinds)];
}

// One row as the learn row sees it; learn() runs a learn row on its pixels
// from offset and gives the sums.
struct LearnRow {
	std::vector<Rgb8> colour;
	std::vector<uint8_t> trimap;
	std::vector<Rgba8> model;

	BoardTeachSums learn(const BoardLearnRows &rows, int offset, int n)
	{
		BoardTeachSums sums;
		rows.learn(colour.data() + offset, trimap.data() + offset, model.data() + offset, n, sums);
		return sums;
	}
};

// Trimap bytes in runs of a few pixels; colour and model bytes at the
// extremes a third of the time each.
LearnRow randomLearnRow(std::mt19937 &rng, int n)
{
	LearnRow r;
	for (uint8_t t = trimapByte(rng); int(r.trimap.size()) < n; t = rng() % 5 ? t : trimapByte(rng)) {
		r.trimap.push_back(t);
		r.colour.push_back({ extremeByte(rng), extremeByte(rng), extremeByte(rng) });
		r.model.push_back({ extremeByte(rng), extremeByte(rng), extremeByte(rng), extremeByte(rng) });
	}
	return r;
}

void expectSameSums(const BoardTeachSums &a, const BoardTeachSums &b, const std::string &what)
{
	for (int k = 0; k < 3; ++k) {
		EXPECT_EQ(a.predicted[k], b.predicted[k]) << what << " channel " << k;
		EXPECT_EQ(a.model[k], b.model[k]) << what << " channel " << k;
	}
}

std::string describe(KernelPath path, int n, int offset)
{
	return std::string(simd_test::pathName(path)) + " n " + std::to_string(n) + " offset " + std::to_string(offset);
}

} // namespace

TEST(BoardLearnRows, EverySimdLearnRowGivesTheCRowsBytesAndSums)
{
	std::mt19937 rng(28);
	for (int n = 0; n <= 67; ++n)
		for (int offset : { 0, 1, 3 })
			for (int trial = 0; trial < 4; ++trial) {
				const LearnRow in = randomLearnRow(rng, n + offset);
				LearnRow want = in;
				const BoardTeachSums wantSums = want.learn(boardLearnRows(KernelPath::C), offset, n);
				for (KernelPath path : simd_test::kSimdPaths) {
					LearnRow got = in;
					const BoardTeachSums sums = got.learn(boardLearnRows(path), offset, n);
					ASSERT_EQ(got.model, want.model) << describe(path, n, offset);
					expectSameSums(sums, wantSums, describe(path, n, offset));
				}
			}
}

// The C row is today's per-pixel rule: a pixel never seen takes the colour
// with one visit, any other board pixel is summed and updated.
TEST(BoardLearnRows, TheCLearnRowIsTheUpdateOfEachBoardPixel)
{
	std::mt19937 rng(3);
	const LearnRow in = randomLearnRow(rng, 500);
	LearnRow got = in;
	const BoardTeachSums sums = got.learn(boardLearnRows(KernelPath::C), 0, 500);
	BoardTeachSums want;
	for (size_t x = 0; x < in.model.size(); ++x) {
		Rgba8 m = in.model[x];
		if (in.trimap[x] == kTrimapBoard) {
			if (m.a) {
				want.predicted[0] += in.colour[x].r, want.predicted[1] += in.colour[x].g;
				want.predicted[2] += in.colour[x].b;
				want.model[0] += m.r, want.model[1] += m.g, want.model[2] += m.b;
			}
			BoardModel::update(m, in.colour[x]);
		}
		ASSERT_EQ(got.model[x], m) << "pixel " << x;
	}
	expectSameSums(sums, want, "C");
}

// Sums gathered in 16-bit lanes must be flushed before they wrap.
TEST(BoardLearnRows, LongBrightRowsSumWithoutWrapping)
{
	const int n = 8192;
	LearnRow row{ std::vector<Rgb8>(n, Rgb8{ 255, 255, 255 }), std::vector<uint8_t>(n, kTrimapBoard),
		      std::vector<Rgba8>(n, Rgba8{ 255, 255, 255, 9 }) };
	for (KernelPath path : simd_test::kAllPaths) {
		LearnRow got = row;
		const BoardTeachSums sums = got.learn(boardLearnRows(path), 0, n);
		for (int k = 0; k < 3; ++k) {
			EXPECT_EQ(sums.predicted[k], uint64_t(255) * n) << simd_test::pathName(path);
			EXPECT_EQ(sums.model[k], uint64_t(255) * n) << simd_test::pathName(path);
		}
	}
}

TEST(BoardLearnRows, EverySimdAlphaOrRowGivesTheCRowsBytes)
{
	std::mt19937 rng(9);
	for (int n = 0; n <= 67; ++n)
		for (int offset : { 0, 1, 5 }) {
			std::vector<uint8_t> a(size_t(n + offset)), b(a.size()), c(a.size());
			for (size_t x = 0; x < a.size(); ++x)
				a[x] = rng() % 4 ? 0 : extremeByte(rng), b[x] = rng() % 4 ? 0 : extremeByte(rng),
				c[x] = rng() % 4 ? 0 : extremeByte(rng);
			std::vector<uint8_t> want(a.size(), 7);
			boardAlphaOrRow_C(a.data() + offset, b.data() + offset, c.data() + offset, want.data() + offset, n);
			for (int x = 0; x < n; ++x)
				ASSERT_EQ(want[size_t(x + offset)], a[size_t(x + offset)] | b[size_t(x + offset)] | c[size_t(x + offset)]);
			for (KernelPath path : simd_test::kSimdPaths) {
				std::vector<uint8_t> got(a.size(), 7);
				boardLearnRows(path).alphaOr(a.data() + offset, b.data() + offset, c.data() + offset,
							     got.data() + offset, n);
				ASSERT_EQ(got, want) << describe(path, n, offset);
			}
		}
}

TEST(BoardLearnRows, EverySimdSelectRowGivesTheCRowsBytes)
{
	std::mt19937 rng(17);
	for (int margin : { 1, 2, 3, 7, 16, 40 })
		for (int n = 0; n <= 67; ++n)
			for (int trial = 0; trial < 3; ++trial) {
				// near is read from -margin to n + margin; lecturer pixels sparse
				// enough that both answers occur.
				std::vector<uint8_t> near(size_t(n + 2 * margin + 1)), trimap(size_t(n + 1));
				for (uint8_t &v : near)
					v = rng() % 8 ? 0 : extremeByte(rng);
				for (uint8_t &t : trimap)
					t = trimapByte(rng);
				const uint8_t *at = near.data() + margin + 1;
				std::vector<uint8_t> want(trimap.size(), 7);
				boardDecidedSelectRow_C(at, trimap.data() + 1, margin, want.data() + 1, n);
				for (int x = 0; x < n; ++x) {
					const uint8_t t = trimap[size_t(x + 1)];
					const bool learned = t != kTrimapBoard && t != kTrimapLecturer && !at[x - margin] &&
							     !at[x] && !at[x + margin];
					ASSERT_EQ(want[size_t(x + 1)], learned ? kTrimapBoard : kTrimapLecturer) << x;
				}
				for (KernelPath path : simd_test::kSimdPaths) {
					std::vector<uint8_t> got(trimap.size(), 7);
					boardLearnRows(path).decidedSelect(at, trimap.data() + 1, margin, got.data() + 1, n);
					ASSERT_EQ(got, want) << describe(path, n, 1) << " margin " << margin;
				}
			}
}
