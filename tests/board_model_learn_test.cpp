// BoardModel::learn() and learnDecided() (now row kernels,
// algo/board_learn_rows.hpp) on every kernel path against the scalar loops
// they replaced, kept here as the reference: the same model bytes, visit
// counts and light gains, frame after frame, on random images with image
// borders, ROIs and margins of every kind.
#include "algo/board_model.hpp"
#include "algo/trimap.hpp"
#include "tests/simd_paths.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

using namespace depthkey;

namespace {

constexpr int kRowStride = BoardModel::kRowStride;

// The model as the scalar code kept it.
struct ReferenceModel {
	RgbaImage model;
	int phase = 0, lastPhase = 0;
	int gains[3] = { 256, 256, 256 };
};

// BoardModel::learn() before the row kernels (the gains as setGains got them).
void referenceLearn(ReferenceModel &ref, const RgbImage &colour, const Gray8Image &trimap)
{
	const int w = colour.width(), h = colour.height();
	if (ref.model.width() != w || ref.model.height() != h) {
		ref.model = RgbaImage(w, h);
		ref.phase = 0;
	}
	uint64_t colourSum[3] = {}, modelSum[3] = {};
	for (int y = ref.phase; y < h; y += kRowStride) {
		const Rgb8 *c = colour.row(y);
		const uint8_t *t = trimap.row(y);
		Rgba8 *m = ref.model.row(y);
		for (int x = 0; x < w; ++x) {
			if (t[x] != kTrimapBoard)
				continue;
			if (m[x].a == 0) {
				m[x] = { c[x].r, c[x].g, c[x].b, 1 };
				continue;
			}
			colourSum[0] += c[x].r;
			colourSum[1] += c[x].g;
			colourSum[2] += c[x].b;
			modelSum[0] += m[x].r;
			modelSum[1] += m[x].g;
			modelSum[2] += m[x].b;
			BoardModel::update(m[x], c[x]);
		}
	}
	for (int k = 0; k < 3; ++k)
		ref.gains[k] = modelSum[k] ? int(std::clamp<uint64_t>((colourSum[k] * 256 + modelSum[k] / 2) / modelSum[k], 128, 512))
					   : 256;
	ref.lastPhase = ref.phase;
	ref.phase = (ref.phase + 1) % kRowStride;
}

// BoardModel::learnDecided() before the row kernels.
void referenceLearnDecided(ReferenceModel &ref, const RgbImage &colour, const Gray8Image &trimap,
			   const Gray8Image &alpha, const Roi &roi, int marginPx)
{
	const int w = colour.width(), h = colour.height();
	if (ref.model.width() != w || ref.model.height() != h || alpha.width() != w || alpha.height() != h || roi.empty())
		return;
	marginPx = std::max(1, marginPx);
	auto clearOfLecturer = [&](int x, int y) {
		for (int dy = -marginPx; dy <= marginPx; dy += marginPx) {
			const int yy = y + dy;
			if (yy < 0 || yy >= h)
				continue;
			const uint8_t *a = alpha.row(yy);
			for (int dx = -marginPx; dx <= marginPx; dx += marginPx) {
				const int xx = x + dx;
				if (xx >= 0 && xx < w && a[xx])
					return false;
			}
		}
		return true;
	};
	const int first = roi.y0 + ((ref.lastPhase - roi.y0 % kRowStride + kRowStride) % kRowStride);
	for (int y = first; y < roi.y1; y += kRowStride) {
		const Rgb8 *c = colour.row(y);
		const uint8_t *t = trimap.row(y);
		Rgba8 *m = ref.model.row(y);
		for (int x = roi.x0; x < roi.x1; ++x)
			if (t[x] != kTrimapBoard && t[x] != kTrimapLecturer && clearOfLecturer(x, y))
				BoardModel::update(m[x], c[x]);
	}
}

// A frame: colours near a board colour or anywhere (0 and 255 included);
// the trimap in runs of every class; the alpha 0 with a few rectangles and
// specks of lecturer, so that a margin finds both clear and covered pixels.
struct Frame {
	RgbImage colour;
	Gray8Image trimap, alpha;
};

Frame randomFrame(std::mt19937 &rng, int w, int h)
{
	Frame f{ RgbImage(w, h), Gray8Image(w, h), Gray8Image(w, h, 0) };
	const uint8_t kinds[] = { kTrimapBoard, kTrimapBoard, kTrimapUndecided, kTrimapUndecided,
				  kTrimapLecturer, kTrimapSubset, kTrimapInRange };
	auto byte = [&] { return rng() % 8 == 0 ? uint8_t(rng() % 2 ? 255 : 0) : uint8_t(rng()); };
	for (int y = 0; y < h; ++y) {
		uint8_t t = kinds[rng() % std::size(kinds)];
		for (int x = 0; x < w; ++x) {
			if (rng() % 7 == 0)
				t = kinds[rng() % std::size(kinds)];
			f.trimap.row(y)[x] = t;
			f.colour.row(y)[x] = rng() % 2 ? Rgb8{ uint8_t(60 + rng() % 8), uint8_t(90 + rng() % 8), uint8_t(70 + rng() % 8) }
						      : Rgb8{ byte(), byte(), byte() };
			if (rng() % 97 == 0)
				f.alpha.row(y)[x] = uint8_t(1 + rng() % 255);
		}
	}
	for (int k = int(rng() % 3); k > 0; --k) {
		const int x0 = int(rng() % unsigned(w)), y0 = int(rng() % unsigned(h));
		const int x1 = std::min(w, x0 + 1 + int(rng() % 12)), y1 = std::min(h, y0 + 1 + int(rng() % 12));
		for (int y = y0; y < y1; ++y)
			std::fill(f.alpha.row(y) + x0, f.alpha.row(y) + x1, uint8_t(255));
	}
	return f;
}

Roi randomRoi(std::mt19937 &rng, int w, int h)
{
	if (rng() % 3 == 0)
		return { 0, 0, w, h }; // the whole image: every border
	const int x0 = int(rng() % unsigned(w)), y0 = int(rng() % unsigned(h));
	return { x0, y0, x0 + 1 + int(rng() % unsigned(w - x0)), y0 + 1 + int(rng() % unsigned(h - y0)) };
}

} // namespace

TEST(BoardModelLearn, LearnAndLearnDecidedAreTheScalarLoopsOnEveryPath)
{
	const int sizes[][2] = { { 1, 1 }, { 2, 5 }, { 5, 2 }, { 17, 9 }, { 33, 20 }, { 67, 13 }, { 130, 31 } };
	for (KernelPath path : simd_test::kAllPaths) {
		std::mt19937 rng(2028);
		for (const auto &size : sizes) {
			const int w = size[0], h = size[1];
			BoardModel model;
			model.setKernelPath(path);
			ReferenceModel ref;
			for (int frame = 0; frame < 12; ++frame) {
				const Frame f = randomFrame(rng, w, h);
				model.learn(f.colour, f.trimap);
				referenceLearn(ref, f.colour, f.trimap);
				const Roi roi = randomRoi(rng, w, h);
				const int margins[] = { 0, 1, 2, 3, 5, 8, 40 }; // 0 is taken as 1; 40 beyond the image
				const int margin = margins[rng() % std::size(margins)];
				model.learnDecided(f.colour, f.trimap, f.alpha, roi, margin);
				referenceLearnDecided(ref, f.colour, f.trimap, f.alpha, roi, margin);
				for (int k = 0; k < 3; ++k)
					ASSERT_EQ(model.gainQ8()[k], ref.gains[k]) << simd_test::pathName(path) << " frame " << frame;
				for (int y = 0; y < h; ++y)
					for (int x = 0; x < w; ++x)
						ASSERT_EQ(model.row(y)[x], ref.model.row(y)[x])
							<< simd_test::pathName(path) << " " << w << "x" << h << " frame " << frame
							<< " at " << x << "," << y << " margin " << margin;
			}
		}
	}
}

// Both paths of learnDecided's rows see the alpha beyond the ROI (a lecturer
// just outside it still keeps the board inside from being learned).
TEST(BoardModelLearn, ALecturerJustOutsideTheRoiStillCovers)
{
	const int w = 40, h = 12;
	RgbImage colour(w, h, Rgb8{ 50, 60, 70 }), later(w, h, Rgb8{ 150, 160, 170 });
	const Gray8Image board(w, h, kTrimapBoard), undecided(w, h, kTrimapUndecided);
	Gray8Image alpha(w, h, 0);
	alpha.row(4)[9] = 255; // three pixels left of the ROI's first column
	for (KernelPath path : simd_test::kAllPaths) {
		BoardModel model;
		model.setKernelPath(path);
		for (int frame = 0; frame < kRowStride; ++frame)
			model.learn(colour, board);
		model.learn(colour, board); // row 0, 4, 8 last
		model.learnDecided(later, undecided, alpha, Roi{ 12, 0, w, h }, 3);
		EXPECT_EQ(model.row(4)[12], (Rgba8{ 50, 60, 70, 2 })) << simd_test::pathName(path);
		EXPECT_NE(model.row(4)[20], (Rgba8{ 50, 60, 70, 2 })) << simd_test::pathName(path);
		EXPECT_EQ(model.row(4)[11], (Rgba8{ 50, 60, 70, 2 })) << simd_test::pathName(path) << " outside the ROI";
	}
}
