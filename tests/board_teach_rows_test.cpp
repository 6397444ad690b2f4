// The board model's teach row (algo/board_teach_rows.hpp): the C row
// against a floating-point reference (within one level), and the SSE2,
// SSSE3 and NEON rows against the C row bit for bit (model bytes and sums),
// for rows of every length about the vector steps, unaligned, with pixels
// never seen, saturated visit counts, and gains from 0 to 32767.
#include "algo/board_model.hpp"
#include "algo/board_teach_rows.hpp"
#include "algo/trimap.hpp"
#include "tests/simd_paths.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

using namespace depthkey;

namespace {

struct Row {
	std::vector<Rgb8> sampled;
	std::vector<uint8_t> mask;
	std::vector<Rgba8> model;
};

// Masks in runs (the display is a big region, the lecturer's silhouette
// cuts it), any bytes besides kTrimapBoard; visit counts 0, 255 and between.
Row randomRow(std::mt19937 &rng, int n)
{
	Row r;
	r.sampled.resize(size_t(n));
	r.mask.resize(size_t(n));
	r.model.resize(size_t(n));
	uint8_t mask = kTrimapBoard;
	for (int x = 0; x < n; ++x) {
		if (rng() % 6 == 0)
			mask = rng() % 2 ? kTrimapBoard : uint8_t(rng());
		r.mask[size_t(x)] = mask;
		r.sampled[size_t(x)] = { uint8_t(rng()), uint8_t(rng()), uint8_t(rng()) };
		const unsigned kind = rng() % 4;
		const uint8_t visits = kind == 0 ? 0 : kind == 1 ? 255 : uint8_t(rng());
		r.model[size_t(x)] = { uint8_t(rng()), uint8_t(rng()), uint8_t(rng()), visits };
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

} // namespace

TEST(BoardTeachRows, EverySimdRowGivesTheCRowsBytesAndSums)
{
	std::mt19937 rng(47);
	const int gainSets[][3] = { { 256, 256, 256 }, { 0, 16, 2048 }, { 32767, 1, 300 }, { 255, 257, 511 } };
	for (int n : { 0, 1, 3, 4, 5, 6, 7, 8, 9, 15, 16, 17, 31, 33, 64, 101, 640 })
		for (int offset : { 0, 1, 3 })
			for (int trial = 0; trial < 6; ++trial) {
				int gains[3];
				if (trial < 4)
					std::copy(gainSets[trial], gainSets[trial] + 3, gains);
				else
					for (int &g : gains)
						g = int(rng() % 32768);
				Row in = randomRow(rng, n + offset);
				Row want = in;
				BoardTeachSums wantSums;
				boardTeachRow_C(want.sampled.data() + offset, want.mask.data() + offset, gains,
						want.model.data() + offset, n, wantSums);
				for (KernelPath path : simd_test::kSimdPaths) {
					Row got = in;
					BoardTeachSums sums;
					boardTeachRow(path, gains)(got.sampled.data() + offset, got.mask.data() + offset, gains,
								   got.model.data() + offset, n, sums);
					const std::string what = std::string(simd_test::pathName(path)) + " n " +
								 std::to_string(n) + " offset " + std::to_string(offset);
					ASSERT_EQ(got.model, want.model) << what;
					expectSameSums(sums, wantSums, what);
				}
			}
}

// Sums gathered in 16-bit lanes must be flushed before they wrap: a long
// row of bright, seen board pixels.
TEST(BoardTeachRows, LongBrightRowsSumWithoutWrapping)
{
	const int n = 8192;
	Row row;
	row.sampled.assign(n, Rgb8{ 255, 255, 255 });
	row.mask.assign(n, kTrimapBoard);
	row.model.assign(n, Rgba8{ 255, 255, 255, 9 });
	const int gains[3] = { 2048, 2048, 2048 };
	for (KernelPath path : simd_test::kAllPaths) {
		Row got = row;
		BoardTeachSums sums;
		boardTeachRow(path, gains)(got.sampled.data(), got.mask.data(), gains, got.model.data(), n, sums);
		for (int k = 0; k < 3; ++k) {
			EXPECT_EQ(sums.predicted[k], uint64_t(255) * n) << simd_test::pathName(path);
			EXPECT_EQ(sums.model[k], uint64_t(255) * n) << simd_test::pathName(path);
		}
	}
}

// The fixed-point row against its meaning in floating point: the prediction
// min(255, v g / 256), the model a quarter of the way to it (a pixel never
// seen takes it whole). Tolerance: one level (the prediction's rounding,
// half a level, and the step's, half a level).
TEST(BoardTeachRows, TheCRowIsTheFloatingPointTeachWithinOneLevel)
{
	std::mt19937 rng(5);
	int worst = 0;
	for (int trial = 0; trial < 200; ++trial) {
		const int gains[3] = { int(rng() % 2049), int(rng() % 2049), int(rng() % 2049) };
		Row row = randomRow(rng, 257);
		Row taught = row;
		BoardTeachSums sums;
		boardTeachRow_C(taught.sampled.data(), taught.mask.data(), gains, taught.model.data(), 257, sums);
		for (size_t x = 0; x < row.model.size(); ++x) {
			const Rgba8 before = row.model[x], after = taught.model[x];
			if (row.mask[x] != kTrimapBoard) {
				ASSERT_EQ(after, before);
				continue;
			}
			const uint8_t v[3] = { row.sampled[x].r, row.sampled[x].g, row.sampled[x].b };
			const uint8_t m[3] = { before.r, before.g, before.b }, got[3] = { after.r, after.g, after.b };
			for (int c = 0; c < 3; ++c) {
				const double p = std::min(255.0, double(v[c]) * gains[c] / 256.0);
				const double want = before.a ? m[c] + (p - m[c]) / 4.0 : p;
				const int error = int(std::ceil(std::abs(got[c] - want) - 1e-9));
				worst = std::max(worst, error);
				ASSERT_LE(std::abs(got[c] - want), 1.0) << "pixel " << x << " channel " << c;
			}
			EXPECT_EQ(after.a, before.a == 255 ? 255 : before.a + 1);
		}
	}
	std::printf("    board teach, fixed vs double: worst %d level\n", worst);
}

TEST(BoardTeachRows, GainsBeyondSixteenBitsRunTheCRow)
{
	const int gains[3] = { 40000, 256, 256 }, negative[3] = { 256, -1, 256 };
	for (KernelPath path : simd_test::kAllPaths) {
		EXPECT_EQ(boardTeachRow(path, gains), &boardTeachRow_C) << simd_test::pathName(path);
		EXPECT_EQ(boardTeachRow(path, negative), &boardTeachRow_C) << simd_test::pathName(path);
	}
}

// The whole model taught through each path: the same bytes and the same
// light gain (seen through distance()).
TEST(BoardTeachRows, BoardModelTeachIsTheSameOnEveryPath)
{
	std::mt19937 rng(11);
	const int w = 203, h = 17;
	RgbImage colour(w, h), sampled(w, h);
	Gray8Image trimap(w, h, kTrimapBoard), display(w, h, kTrimapBoard);
	for (int y = 0; y < h; ++y)
		for (int x = 0; x < w; ++x) {
			colour.row(y)[x] = { uint8_t(rng()), uint8_t(rng()), uint8_t(rng()) };
			sampled.row(y)[x] = { uint8_t(rng()), uint8_t(rng()), uint8_t(rng()) };
			if (x > 150)
				display.row(y)[x] = kTrimapLecturer; // off the display
		}
	const int gains[3] = { 300, 250, 270 };
	std::vector<BoardModel> models(5);
	size_t i = 0;
	for (KernelPath path : simd_test::kAllPaths) {
		BoardModel &model = models[i++];
		model.setKernelPath(path);
		model.learn(colour, trimap); // one row in kRowStride seen, the rest never
		for (int frame = 0; frame < 3; ++frame)
			model.teach(sampled, gains, display);
	}
	for (size_t k = 1; k < models.size(); ++k)
		for (int y = 0; y < h; ++y)
			for (int x = 0; x < w; ++x) {
				ASSERT_EQ(models[k].row(y)[x], models[0].row(y)[x]) << "path " << k << " at " << x << "," << y;
				ASSERT_EQ(models[k].distance(x, y, colour.row(y)[x]), models[0].distance(x, y, colour.row(y)[x]));
			}
}
