// The board-geometry warp and composite (algo/board_compositor.hpp) against
// a floating-point reference, the identity warp against the camera-geometry
// kernel bit for bit, what lies outside the camera's view or the ROI, and no
// allocation per frame.
#include "algo/board_compositor.hpp"
#include "algo/changed_rows.hpp"
#include "algo/composite.hpp"
#include "tests/allocation_counter.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

using namespace depthkey;

namespace {

constexpr int kCw = 80, kCh = 60;    // colour image
constexpr int kBw = 150, kBh = 100;  // board output

// A projective view: the board a little turned, the camera seeing part of it.
Homography tiltedView()
{
	Homography h;
	h.h = { 1.7, 0.12, 8.0, -0.05, 1.6, 5.0, 0.0009, -0.0006, 1.0 };
	return h;
}

struct Scene {
	RgbImage colour{ kCw, kCh };
	Gray8Image alpha{ kCw, kCh };
	RgbImage board{ kBw, kBh };
	Roi roi{ 12, 8, 61, 52 };
};

// Smooth colour (bilinear makes sense), random alpha inside the ROI with
// soft and hard edges, 0 outside it, a textured board.
Scene makeScene(uint32_t seed)
{
	Scene s;
	std::mt19937 rng(seed);
	std::uniform_int_distribution<int> any(0, 255);
	for (int y = 0; y < kCh; ++y)
		for (int x = 0; x < kCw; ++x) {
			s.colour.at(x, y) = { uint8_t(3 * x), uint8_t(4 * y), uint8_t(any(rng)) };
			bool in = x >= s.roi.x0 && x < s.roi.x1 && y >= s.roi.y0 && y < s.roi.y1;
			int a = any(rng);
			s.alpha.at(x, y) = in ? uint8_t(a < 60 ? 0 : a > 200 ? 255 : a) : 0;
		}
	for (int y = 0; y < kBh; ++y)
		for (int x = 0; x < kBw; ++x)
			s.board.at(x, y) = { uint8_t(any(rng)), uint8_t((x * 7) & 255), uint8_t(y * 2) };
	return s;
}

// The reference in doubles: the exact inverse map, bilinear colour and
// alpha, composite = board (1 - o a) + colour o a.
struct Reference {
	double r, g, b, a;
	bool seen;
};
Reference reference(const Scene &s, const Homography &h, double opacity, int x, int y,
		    const RadialLens &lens = RadialLens{})
{
	Homography inv;
	h.inverse(inv);
	double ix = -1e9, iy = -1e9, sx = -1e9, sy = -1e9;
	inv.apply(x, y, ix, iy);
	if (!lens.distort(ix, iy, sx, sy))
		sx = sy = -1e9;
	if (!(sx >= -0.5 && sx <= kCw - 0.5 && sy >= -0.5 && sy <= kCh - 0.5)) {
		const Rgb8 &b = s.board.at(x, y);
		return { double(b.r), double(b.g), double(b.b), 0, false };
	}
	// The same edge rule as the kernel: the sample point stays inside.
	sx = std::clamp(sx, 0.0, kCw - 1 - 1.0 / 256);
	sy = std::clamp(sy, 0.0, kCh - 1 - 1.0 / 256);
	int x0 = int(sx), y0 = int(sy);
	double fx = sx - x0, fy = sy - y0;
	auto mix = [&](auto get) {
		return (get(x0, y0) * (1 - fx) + get(x0 + 1, y0) * fx) * (1 - fy) +
		       (get(x0, y0 + 1) * (1 - fx) + get(x0 + 1, y0 + 1) * fx) * fy;
	};
	double a = mix([&](int u, int v) { return double(s.alpha.at(u, v)); }) / 255.0;
	double c[3] = { mix([&](int u, int v) { return double(s.colour.at(u, v).r); }),
			mix([&](int u, int v) { return double(s.colour.at(u, v).g); }),
			mix([&](int u, int v) { return double(s.colour.at(u, v).b); }) };
	const Rgb8 &b = s.board.at(x, y);
	double w = opacity * a;
	return { b.r * (1 - w) + c[0] * w, b.g * (1 - w) + c[1] * w, b.b * (1 - w) + c[2] * w, a * 255.0, true };
}

// The pipeline's camera-geometry lecturer layer: the compositor's input.
RgbaImage layerOf(const RgbImage &colour, const Gray8Image &alpha)
{
	RgbaImage layer;
	lecturerLayer(colour, alpha, layer, KernelPath::C);
	return layer;
}

// The lecturer layer of a 20x22 box of the scene's alpha (made opaque
// enough to warp) that walks step px right a frame and bobs down.
RgbaImage walkingBox(const Scene &s, int frame, int step, Roi &box)
{
	Gray8Image alpha(kCw, kCh, 0);
	box = { 2 + step * frame, 3 + 3 * (frame % 4), std::min(kCw, 22 + step * frame), 25 + 3 * (frame % 4) };
	for (int y = box.y0; y < box.y1; ++y)
		for (int x = box.x0; x < box.x1; ++x)
			alpha.at(x, y) = s.alpha.at(x, y) | 64;
	return layerOf(s.colour, alpha);
}

// Tolerance: Q8 map coordinates (1/512 px rounding) and Q8 weights with one
// rounding each for the sample and the blend: at most 2 levels per channel
// on these images, under 0.3 on average.
struct Agreement {
	double worst = 0, mean = 0;
	size_t seen = 0, lecturerPixels = 0;
};

Agreement composeAgainstReference(const Homography &h, const RadialLens &lens)
{
	Scene s = makeScene(7);
	BoardCompositor compositor;
	Agreement a;
	EXPECT_TRUE(compositor.configure(h, kCw, kCh, kBw, kBh, lens));
	RgbImage composite;
	RgbaImage lecturer;
	const int opacityQ8 = opacityToQ8(0.6);
	compositor.compose(layerOf(s.colour, s.alpha), s.roi, s.board, opacityQ8, composite, lecturer);
	double sum = 0;
	size_t n = 0;
	for (int y = 0; y < kBh; ++y)
		for (int x = 0; x < kBw; ++x) {
			Reference ref = reference(s, h, opacityQ8 / 256.0, x, y, lens);
			const Rgb8 &c = composite.at(x, y);
			const Rgba8 &l = lecturer.at(x, y);
			for (double d : { c.r - ref.r, c.g - ref.g, c.b - ref.b, l.a - ref.a }) {
				a.worst = std::max(a.worst, std::fabs(d));
				sum += std::fabs(d);
				n++;
			}
			a.seen += ref.seen;
			a.lecturerPixels += l.a > 0;
		}
	a.mean = sum / n;
	return a;
}

} // namespace

TEST(BoardCompositor, MatchesTheFloatingPointReference)
{
	Agreement a = composeAgainstReference(tiltedView(), RadialLens{});
	EXPECT_LE(a.worst, 2.0);
	EXPECT_LT(a.mean, 0.3);
	// The test means something: the camera sees part of the board, and the
	// lecturer covers some of that.
	EXPECT_GT(a.seen, size_t(kBw * kBh / 4));
	EXPECT_LT(a.seen, size_t(kBw * kBh));
	EXPECT_GT(a.lecturerPixels, size_t(1000));
}

// The lens folded into the map: the same tolerance against the reference
// that distorts in doubles, and the lens moves pixels (the pinhole map
// would not pass).
TEST(BoardCompositor, WithALensMatchesTheFloatingPointReference)
{
	const RadialLens lens = RadialLens::forImage(kCw, kCh, -0.09, 0.02);
	Agreement a = composeAgainstReference(tiltedView(), lens);
	EXPECT_LE(a.worst, 2.0);
	EXPECT_LT(a.mean, 0.3);
	EXPECT_GT(a.seen, size_t(kBw * kBh / 4));
	EXPECT_GT(a.lecturerPixels, size_t(1000));
	double x, y;
	lens.distort(0, 0, x, y);
	EXPECT_GT(std::hypot(x, y), 1.0) << "the lens should move the corner by more than a pixel";
}

// With H the identity the warp samples whole pixels: the camera-geometry
// composite, byte for byte.
TEST(BoardCompositor, IdentityWarpIsTheCameraComposite)
{
	Scene s = makeScene(3);
	RgbImage board(kCw, kCh);
	for (int y = 0; y < kCh; ++y)
		std::copy(s.board.row(y), s.board.row(y) + kCw, board.row(y));
	BoardCompositor compositor;
	ASSERT_TRUE(compositor.configure(Homography{}, kCw, kCh, kCw, kCh));
	RgbImage warped, camera;
	RgbaImage lecturer, cameraLayer;
	compositor.compose(layerOf(s.colour, s.alpha), s.roi, board, 128, warped, lecturer);
	compositeRoi(s.colour, s.alpha, board, s.roi, 128, camera, KernelPath::C);
	lecturerLayer(s.colour, s.alpha, cameraLayer, KernelPath::C);
	// The last row and column sample 1/256 px in (see the map's edge rule).
	for (int y = 0; y < kCh - 1; ++y)
		for (int x = 0; x < kCw - 1; ++x) {
			ASSERT_EQ(warped.at(x, y).r, camera.at(x, y).r) << x << "," << y;
			ASSERT_EQ(warped.at(x, y).g, camera.at(x, y).g) << x << "," << y;
			ASSERT_EQ(warped.at(x, y).b, camera.at(x, y).b) << x << "," << y;
			ASSERT_EQ(lecturer.at(x, y).a, cameraLayer.at(x, y).a) << x << "," << y;
			if (lecturer.at(x, y).a) {
				ASSERT_EQ(lecturer.at(x, y).r, cameraLayer.at(x, y).r) << x << "," << y;
			}
		}
}

// The lecturer moves: where he was is transparent again, the composite is
// the board there, and outside the warped region nothing was touched.
TEST(BoardCompositor, ClearsWhereTheLecturerWasAndKeepsTheBoardElsewhere)
{
	Scene s = makeScene(11);
	BoardCompositor compositor;
	ASSERT_TRUE(compositor.configure(tiltedView(), kCw, kCh, kBw, kBh));
	RgbImage composite;
	RgbaImage lecturer;
	compositor.compose(layerOf(s.colour, s.alpha), s.roi, s.board, 256, composite, lecturer);
	Roi first = compositor.warpedRoi();
	ASSERT_FALSE(first.empty());

	// Now he stands in a small box at the left only.
	Gray8Image alpha(kCw, kCh, 0);
	Roi small{ 2, 2, 10, 10 };
	for (int y = small.y0; y < small.y1; ++y)
		for (int x = small.x0; x < small.x1; ++x)
			alpha.at(x, y) = 255;
	compositor.compose(layerOf(s.colour, alpha), small, s.board, 256, composite, lecturer);
	Roi second = compositor.warpedRoi();
	size_t lit = 0;
	for (int y = 0; y < kBh; ++y)
		for (int x = 0; x < kBw; ++x) {
			bool inSecond = x >= second.x0 && x < second.x1 && y >= second.y0 && y < second.y1;
			if (!inSecond) {
				ASSERT_EQ(lecturer.at(x, y).a, 0) << x << "," << y;
				ASSERT_EQ(composite.at(x, y).r, s.board.at(x, y).r) << x << "," << y;
			}
			lit += lecturer.at(x, y).a == 255;
		}
	EXPECT_GT(lit, size_t(100)); // the 8x8 box at about 1.7x
}

// The outputs are kept between frames (the board copied and the layer
// cleared only where he was): frame by frame, as he moves and the board
// picture changes, they are byte for byte what a fresh compositor writes
// into fresh buffers. A buffer it did not write last is written whole.
TEST(BoardCompositor, KeptOutputsEqualFreshOnesAsHeMovesAndTheBoardChanges)
{
	Scene s = makeScene(21);
	BoardCompositor kept;
	ASSERT_TRUE(kept.configure(tiltedView(), kCw, kCh, kBw, kBh));
	RgbImage composite;
	RgbaImage lecturer;
	for (int frame = 0; frame < 12; ++frame) {
		// A box that walks right and down, and a new board at frame 5.
		Roi box;
		const RgbaImage source = walkingBox(s, frame, 5, box);
		if (frame == 5) {
			s.board = makeScene(22).board;
			kept.forgetBoard();
		}
		kept.compose(source, box, s.board, 200, composite, lecturer);
		if (frame == 9) {
			// Someone else's buffers: garbage, which must all be overwritten.
			composite = RgbImage(kBw, kBh, Rgb8{ 1, 2, 3 });
			lecturer = RgbaImage(kBw, kBh, Rgba8{ 9, 9, 9, 9 });
			kept.compose(source, box, s.board, 200, composite, lecturer);
		}
		BoardCompositor fresh;
		ASSERT_TRUE(fresh.configure(tiltedView(), kCw, kCh, kBw, kBh));
		RgbImage freshComposite;
		RgbaImage freshLecturer;
		fresh.compose(source, box, s.board, 200, freshComposite, freshLecturer);
		ASSERT_EQ(0, std::memcmp(composite.data(), freshComposite.data(), composite.size() * sizeof(Rgb8)))
			<< "frame " << frame;
		ASSERT_EQ(0, std::memcmp(lecturer.data(), freshLecturer.data(), lecturer.size() * sizeof(Rgba8)))
			<< "frame " << frame;
	}
}

// Written into a ring's slots (issue 29 §2): a pair of buffers a slot,
// each holding what the compositor wrote there slots frames ago (or a
// repeated frame's copy, or someone else's garbage); frame by frame, what
// it writes is byte for byte what a fresh compositor writes into fresh
// images (the path that copied them into the slots).
// Whether a slot holds what a fresh compositor makes of the same frame.
static bool equalsFreshComposite(const RgbaImage &source, const Roi &box, const RgbImage &board, const RgbImage &composite,
				 const RgbaImage &layer)
{
	BoardCompositor fresh;
	if (!fresh.configure(tiltedView(), kCw, kCh, kBw, kBh))
		return false;
	RgbImage freshComposite;
	RgbaImage freshLecturer;
	fresh.compose(source, box, board, 200, freshComposite, freshLecturer);
	return composite == freshComposite && layer == freshLecturer;
}

TEST(BoardCompositor, RingSlotsEqualFreshImagesAsHeMovesAndTheBoardChanges)
{
	for (int slots : { 2, 3 }) {
		Scene s = makeScene(31);
		BoardCompositor kept;
		ASSERT_TRUE(kept.configure(tiltedView(), kCw, kCh, kBw, kBh));
		std::vector<RgbImage> composites(slots, RgbImage(kBw, kBh, Rgb8{ 5, 6, 7 }));
		std::vector<RgbaImage> layers(slots, RgbaImage(kBw, kBh, Rgba8{ 8, 8, 8, 8 }));
		std::vector<uint64_t> holds(slots, 0);
		for (int frame = 1; frame <= 16; ++frame) {
			const int slot = frame % slots, last = (frame - 1) % slots;
			if (frame == 7 || frame == 8) { // repeated frames: the last slot copied, its tag too
				composites[slot] = composites[last];
				layers[slot] = layers[last];
				holds[slot] = holds[last];
				continue;
			}
			if (frame == 11) { // someone else wrote this slot: written whole
				composites[slot] = RgbImage(kBw, kBh, Rgb8{ 1, 2, 3 });
				holds[slot] = 0;
			}
			Roi box;
			const RgbaImage source = walkingBox(s, frame, 4, box);
			if (frame == 5) {
				s.board = makeScene(32).board;
				kept.forgetBoard();
			}
			holds[slot] = kept.compose(source, box, s.board, 200,
						   { viewOf(composites[slot]), viewOf(layers[slot]), holds[slot] });
			EXPECT_NE(holds[slot], 0u);
			ASSERT_TRUE(equalsFreshComposite(source, box, s.board, composites[slot], layers[slot]))
				<< slots << " slots, frame " << frame;
		}
	}
}

// The board changed in some rows only (a stroke more, said by
// forgetBoardRows): each slot gets only those rows again, and still equals
// a fresh composite; a slot that missed more changes than are remembered
// is written whole.
TEST(BoardCompositor, RingSlotsGetOnlyTheChangedRowsOfTheBoardAndStillEqualFreshImages)
{
	for (int slots : { 2, 3 }) {
		Scene s = makeScene(41);
		BoardCompositor kept, imagesKept; // into ring slots; into its own pair of images
		ASSERT_TRUE(kept.configure(tiltedView(), kCw, kCh, kBw, kBh));
		ASSERT_TRUE(imagesKept.configure(tiltedView(), kCw, kCh, kBw, kBh));
		RgbImage composite;
		RgbaImage layer;
		std::vector<RgbImage> composites(slots, RgbImage(kBw, kBh, Rgb8{ 5, 6, 7 }));
		std::vector<RgbaImage> layers(slots, RgbaImage(kBw, kBh, Rgba8{ 8, 8, 8, 8 }));
		std::vector<uint64_t> holds(slots, 0);
		for (int frame = 1; frame <= 24; ++frame) {
			const int slot = frame % slots;
			const RgbImage before = s.board;
			// A stroke in a band of rows on most frames; none on every 4th.
			if (frame % 4 != 0) {
				const int y0 = (frame * 13) % (kBh - 3);
				for (int y = y0; y < y0 + 3; ++y)
					for (int x = frame % 7; x < kBw; x += 2)
						s.board.at(x, y) = Rgb8{ uint8_t(200 + frame), 200, 190 };
			}
			if (frame == 17) // many changes while this slot waits: more than remembered
				for (int k = 0; k < 20; ++k) {
					s.board.at(k, k) = Rgb8{ uint8_t(k), 1, 1 };
					kept.forgetBoardRows(k, k);
					imagesKept.forgetBoardRows(k, k);
				}
			const RowRange changed = changedRows(before, s.board);
			kept.forgetBoardRows(changed.first, changed.last);
			imagesKept.forgetBoardRows(changed.first, changed.last);
			Roi box;
			const RgbaImage source = walkingBox(s, frame, 4, box);
			holds[slot] = kept.compose(source, box, s.board, 200,
						   { viewOf(composites[slot]), viewOf(layers[slot]), holds[slot] });
			ASSERT_TRUE(equalsFreshComposite(source, box, s.board, composites[slot], layers[slot]))
				<< slots << " slots, frame " << frame;
			imagesKept.compose(source, box, s.board, 200, composite, layer);
			ASSERT_TRUE(equalsFreshComposite(source, box, s.board, composite, layer)) << "images, frame " << frame;
		}
	}
}

// A target of another size than the output is never written past: the
// board alone where it fits, tag 0 (its contents not known next time).
TEST(BoardCompositor, ATargetOfAnotherSizeIsNotWrittenPast)
{
	Scene s = makeScene(3);
	BoardCompositor compositor;
	ASSERT_TRUE(compositor.configure(tiltedView(), kCw, kCh, kBw, kBh));
	RgbImage composite(kBw, kBh - 1, Rgb8{ 1, 1, 1 });
	RgbaImage lecturer(kBw, kBh - 1, Rgba8{ 9, 9, 9, 9 });
	EXPECT_EQ(compositor.compose(layerOf(s.colour, s.alpha), s.roi, s.board, 256,
				     { viewOf(composite), viewOf(lecturer), 0 }),
		  0u);
	EXPECT_EQ(composite.at(3, 3), Rgb8({ 1, 1, 1 })); // the board does not fit it either
	EXPECT_EQ(lecturer.at(3, 3), Rgba8({ 0, 0, 0, 0 }));
}

TEST(BoardCompositor, RefusesASingularHomographyAndMismatchedSizes)
{
	BoardCompositor compositor;
	Homography flat;
	flat.h = { 1, 2, 0, 2, 4, 0, 0, 0, 1 };
	EXPECT_FALSE(compositor.configure(flat, kCw, kCh, kBw, kBh));
	EXPECT_FALSE(compositor.configured());
	ASSERT_TRUE(compositor.configure(tiltedView(), kCw, kCh, kBw, kBh));
	// A colour frame of another size gives the board alone, never a read
	// out of bounds.
	Scene s = makeScene(1);
	RgbImage small(20, 20, Rgb8{ 1, 2, 3 });
	Gray8Image smallAlpha(20, 20, 255);
	RgbImage composite;
	RgbaImage lecturer;
	compositor.compose(layerOf(small, smallAlpha), Roi{ 0, 0, 20, 20 }, s.board, 256, composite, lecturer);
	EXPECT_EQ(composite.at(70, 50).r, s.board.at(70, 50).r);
	EXPECT_EQ(lecturer.at(70, 50).a, 0);
}

TEST(BoardCompositor, AllocatesNothingPerFrame)
{
	if (!test::allocationCounting())
		GTEST_SKIP() << "allocations are not counted in sanitizer builds";
	Scene s = makeScene(5);
	BoardCompositor compositor;
	ASSERT_TRUE(compositor.configure(tiltedView(), kCw, kCh, kBw, kBh));
	RgbImage composite;
	RgbaImage lecturer, source = layerOf(s.colour, s.alpha);
	compositor.compose(source, s.roi, s.board, 128, composite, lecturer); // sizes the outputs
	test::CountAllocations count;
	for (int i = 0; i < 20; ++i) {
		Roi roi{ s.roi.x0 + i % 5, s.roi.y0, s.roi.x1 - i % 3, s.roi.y1 };
		compositor.compose(source, roi, s.board, 128, composite, lecturer);
	}
	EXPECT_EQ(count.count(), 0u);
}

TEST(BoardCompositor, AllocatesNothingPerFrameIntoRingSlots)
{
	if (!test::allocationCounting())
		GTEST_SKIP() << "allocations are not counted in sanitizer builds";
	Scene s = makeScene(6);
	BoardCompositor compositor;
	ASSERT_TRUE(compositor.configure(tiltedView(), kCw, kCh, kBw, kBh));
	RgbImage composites[2] = { RgbImage(kBw, kBh), RgbImage(kBw, kBh) };
	RgbaImage layers[2] = { RgbaImage(kBw, kBh), RgbaImage(kBw, kBh) }, source = layerOf(s.colour, s.alpha);
	uint64_t holds[2] = {};
	test::CountAllocations count;
	for (int i = 0; i < 20; ++i) {
		Roi roi{ s.roi.x0 + i % 5, s.roi.y0, s.roi.x1 - i % 3, s.roi.y1 };
		holds[i % 2] = compositor.compose(source, roi, s.board, 128,
						  { viewOf(composites[i % 2]), viewOf(layers[i % 2]), holds[i % 2] });
	}
	EXPECT_EQ(count.count(), 0u);
}
