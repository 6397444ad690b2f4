// The fixed-point guided filter against a double reference of He et al.'s
// filter (windows clipped to the ROI, computed at every pixel): within 2
// levels everywhere (the reference's own a, b are not rounded), and the edge
// of a staircase matte moves onto the colour image's edge; and equal, bit
// for bit, to the whole-ROI filter it replaced (issue 28) on lecture frames.
#include <gtest/gtest.h>

#include "algo/guided_filter.hpp"
#include "tests/edge_scenes.hpp"
#include "tests/guided_filter_whole_roi.hpp"
#include "tests/simd_paths.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <vector>

using namespace depthkey;

namespace {

void referenceGuided(const RgbImage &colour, const Gray8Image &matte, const Roi &roi, int r, double eps,
		     std::vector<double> &q)
{
	const int w = roi.x1 - roi.x0, h = roi.y1 - roi.y0;
	auto I = [&](int x, int y) {
		const Rgb8 c = colour.at(roi.x0 + x, roi.y0 + y);
		return double((c.r + 2 * c.g + c.b + 2) / 4);
	};
	auto P = [&](int x, int y) { return double(matte.at(roi.x0 + x, roi.y0 + y)); };
	std::vector<double> a(size_t(w) * h), b(size_t(w) * h);
	auto windowed = [&](int x, int y, auto f) {
		double s = 0;
		int n = 0;
		for (int yy = std::max(0, y - r); yy < std::min(h, y + r + 1); ++yy)
			for (int xx = std::max(0, x - r); xx < std::min(w, x + r + 1); ++xx, ++n)
				s += f(xx, yy);
		return s / n;
	};
	for (int y = 0; y < h; ++y)
		for (int x = 0; x < w; ++x) {
			const double mI = windowed(x, y, I), mP = windowed(x, y, P);
			const double mII = windowed(x, y, [&](int u, int v) { return I(u, v) * I(u, v); });
			const double mIP = windowed(x, y, [&](int u, int v) { return I(u, v) * P(u, v); });
			const double ak = (mIP - mI * mP) / (mII - mI * mI + eps);
			a[size_t(y) * w + x] = ak;
			b[size_t(y) * w + x] = mP - ak * mI;
		}
	q.assign(size_t(w) * h, 0);
	for (int y = 0; y < h; ++y)
		for (int x = 0; x < w; ++x) {
			const double ma = windowed(x, y, [&](int u, int v) { return a[size_t(v) * w + u]; });
			const double mb = windowed(x, y, [&](int u, int v) { return b[size_t(v) * w + u]; });
			q[size_t(y) * w + x] = std::clamp(ma * I(x, y) + mb, 0.0, 255.0);
		}
}

// A bright shirt on a dark board with noise; the matte a blocky version of
// the shirt (4-pixel steps, as ToF pixels mapped into colour), with the true
// edge at x = 30.
void scene(RgbImage &colour, Gray8Image &matte, int seed)
{
	std::mt19937 random(seed);
	std::normal_distribution<double> noise(0, 3);
	colour = RgbImage(64, 48);
	matte = Gray8Image(64, 48, 0);
	for (int y = 0; y < 48; ++y)
		for (int x = 0; x < 64; ++x) {
			const int v = x < 30 ? 210 : 35;
			auto level = [&](int base) { return uint8_t(std::clamp(int(std::lround(base + noise(random))), 0, 255)); };
			colour.at(x, y) = { level(v), level(v), level(v - 5) };
			const int blockyEdge = 28 + 4 * ((y / 8) % 2); // 28 or 32
			matte.at(x, y) = x < blockyEdge && x > 2 && y > 2 && y < 45 ? 255 : 0;
		}
}

} // namespace

TEST(GuidedFilter, FixedPointMatchesTheDoubleReferenceWithin2Levels)
{
	// eps 10 (the shipped default, about the noise's square: the filter
	// follows weak edges and divides by small variances) and 400 (smooth).
	for (int eps : { 10, 400 })
	for (int seed : { 1, 2 })
		for (int radius : { 2, 3, 5 }) {
			RgbImage colour;
			Gray8Image matte, out;
			scene(colour, matte, seed);
			const Roi roi{ 1, 1, 63, 47 };
			GuidedFilter filter;
			filter.configure(radius, eps);
			filter.filter(colour, matte, roi, out);
			std::vector<double> ref;
			referenceGuided(colour, matte, roi, radius, double(eps), ref);
			std::map<int, int> histogram;
			int worst = 0;
			for (int y = roi.y0; y < roi.y1; ++y)
				for (int x = roi.x0; x < roi.x1; ++x) {
					const double r = ref[size_t(y - roi.y0) * (roi.x1 - roi.x0) + (x - roi.x0)];
					const int e = int(std::ceil(std::abs(out.at(x, y) - r) - 1e-9));
					histogram[e]++;
					worst = std::max(worst, e);
				}
			std::printf("guided filter r=%d eps=%d seed %d, |fixed - double| histogram:", radius, eps, seed);
			for (auto [e, n] : histogram)
				std::printf(" %d:%d", e, n);
			std::printf("\n");
			EXPECT_LE(worst, 2);
		}
}

TEST(GuidedFilter, TheStaircaseEdgeMovesOntoTheColourEdge)
{
	RgbImage colour;
	Gray8Image matte, out;
	scene(colour, matte, 3);
	GuidedFilter filter;
	filter.configure(3, 400);
	filter.filter(colour, matte, Roi{ 0, 0, 64, 48 }, out);
	// On rows whose blocky edge was at 28 and at 32, the filtered matte
	// crosses one half between x = 29 and x = 30, where the shirt ends.
	for (int y : { 12, 20, 28, 36 }) {
		EXPECT_GE(out.at(29, y), 128) << "row " << y;
		EXPECT_LT(out.at(30, y), 128) << "row " << y;
	}
	EXPECT_GT(filter.changedPixels(), 0u);
}

// The box sums slide over a ring of rows (issue 15): ROIs shorter and
// narrower than a window, at the image's border, one after another on the
// same filter, still match the reference, and nothing outside the ROI moves.
TEST(GuidedFilter, SmallAndBorderRoisMatchTheReferenceOneAfterAnother)
{
	RgbImage colour;
	Gray8Image matte;
	scene(colour, matte, 3);
	GuidedFilter filter;
	for (const Roi &roi : { Roi{ 26, 10, 33, 14 }, Roi{ 0, 0, 64, 48 }, Roi{ 28, 0, 31, 48 }, Roi{ 0, 20, 64, 22 },
				Roi{ 60, 44, 64, 48 }, Roi{ 20, 5, 40, 30 } })
		for (int radius : { 1, 4, 7 }) {
			filter.configure(radius, 400);
			Gray8Image out(64, 48, 77);
			filter.filter(colour, matte, roi, out);
			std::vector<double> ref;
			referenceGuided(colour, matte, roi, radius, 400.0, ref);
			int worst = 0, outside = 0;
			for (int y = 0; y < 48; ++y)
				for (int x = 0; x < 64; ++x) {
					if (x < roi.x0 || x >= roi.x1 || y < roi.y0 || y >= roi.y1) {
						outside += out.at(x, y) != 77;
						continue;
					}
					const double r = ref[size_t(y - roi.y0) * (roi.x1 - roi.x0) + (x - roi.x0)];
					worst = std::max(worst, int(std::ceil(std::abs(out.at(x, y) - r) - 1e-9)));
				}
			EXPECT_LE(worst, 2) << "roi " << roi.x0 << "," << roi.y0 << " r " << radius;
			EXPECT_EQ(outside, 0);
		}
}

// Working only near the edge (issue 28) changes nothing: lecture frames at
// odd and even sizes, every kind of ROI (borders, smaller than a window,
// one pixel thin, empty), each radius, mattes with no edge (all board, all
// lecturer), one filter after another as in the pipeline.
TEST(GuidedFilter, EqualsTheWholeRoiFilterBitForBit)
{
	GuidedFilter filter;
	test::GuidedFilterWholeRoi reference;
	size_t compared = 0, changed = 0;
	for (auto [w, h] : { std::pair{ 160, 120 }, std::pair{ 161, 97 }, std::pair{ 33, 17 } }) {
		test::EdgeScene scene = test::lectureEdgeScene(w, h, 9.0, w > 100 ? 4 : 3);
		const Gray8Image lecturer = scene.matte;
		for (int matte = 0; matte < 3; ++matte) {
			if (matte > 0) // no edge at all
				scene.matte = Gray8Image(w, h, matte == 1 ? 0 : 255);
			else
				scene.matte = lecturer;
			for (const Roi &roi : test::edgeSceneRois(w, h))
				for (int radius = 1; radius <= GuidedFilter::kMaxRadius; ++radius)
					for (int eps : { 10, 400 })
					for (KernelPath path : simd_test::kAllPaths) { // the column sums' rows
						filter.setKernelPath(path);
						filter.configure(radius, eps);
						reference.configure(radius, eps);
						Gray8Image out(w, h, 77), expected(w, h, 77);
						filter.filter(scene.colour, scene.matte, roi, out);
						reference.filter(scene.colour, scene.matte, roi, expected);
						int differ = 0;
						for (int y = 0; y < h; ++y)
							for (int x = 0; x < w; ++x)
								differ += out.at(x, y) != expected.at(x, y);
						ASSERT_EQ(differ, 0) << w << "x" << h << " matte " << matte << " roi " << roi.x0 << ","
								     << roi.y0 << "-" << roi.x1 << "," << roi.y1 << " r " << radius
								     << " eps " << eps << " " << simd_test::pathName(path);
						ASSERT_EQ(filter.changedPixels(), reference.changedPixels());
						compared += size_t(w) * h;
						changed += filter.changedPixels();
					}
		}
	}
	EXPECT_GT(changed, 1000u); // the lecture's edges did move
	std::printf("guided filter: %zu pixels compared, %zu changed by the filter\n", compared, changed);
}
