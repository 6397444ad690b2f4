// The simulator's compact per-pixel colour table (hal/sim/colour_backdrop.hpp)
// against the rule it stands for: off the board the static colour, on it the
// texel's ink while the ink is there, else its background.
#include "hal/sim/colour_backdrop.hpp"
#include "hal/sim/hash_noise.hpp"

#include <algorithm>
#include <gtest/gtest.h>

using namespace depthkey;
using namespace depthkey::sim;

namespace {

Rgb8 direct(int32_t texel, Rgb8 staticColour, const std::vector<BoardTexel> &raster, uint16_t tick)
{
	if (texel < 0)
		return staticColour;
	const BoardTexel &t = raster[size_t(texel)];
	bool inked = t.ink && tick >= t.writeTick && tick < t.eraseTick;
	return inked ? LectureScript::inkColours()[t.ink] : t.background;
}

} // namespace

TEST(ColourBackdrop, SameColoursAsTheTexelsKeptWhole)
{
	const int columns = BoardGeometry::texelColumns(), rows = BoardGeometry::texelRows();
	// Pixels off the board, runs of neighbouring texels (steps of a byte),
	// jumps across the raster (escapes), the first and last texel.
	std::vector<int32_t> texelOf;
	std::vector<Rgb8> staticColour;
	const int width = 200, height = 100;
	for (int k = 0; k < width * height; ++k) {
		uint64_t h = mixHash(k);
		int32_t t;
		if (h % 7 == 0)
			t = -1;
		else if (h % 11 == 0 || texelOf.empty() || texelOf.back() < 0)
			t = int32_t((h >> 8) % (uint64_t(columns) * rows));
		else
			t = std::clamp<int32_t>(texelOf.back() + int((h >> 8) % 15) - 7 + (int((h >> 16) % 15) - 7) * columns,
						0, columns * rows - 1);
		texelOf.push_back(k == 1 ? 0 : k == 2 ? columns * rows - 1 : t);
		// Rows of many colours (kept whole) and of few (a palette).
		if ((k / width) % 2)
			staticColour.push_back({ uint8_t(h >> 24), uint8_t(h >> 32), uint8_t(h >> 40) });
		else
			staticColour.push_back({ uint8_t(h % 3 * 80), 40, 50 });
	}
	ColourBackdrop backdrop;
	backdrop.build(width, texelOf, staticColour);
	for (int cycle = 0; cycle < 2; ++cycle) {
		std::vector<BoardTexel> raster(size_t(columns) * rows);
		for (size_t i = 0; i < raster.size(); ++i) {
			uint64_t h = mixHash(i * 2 + cycle);
			// The first cycle's slide of many colours, the second's of few.
			raster[i].background = cycle == 0 ? Rgb8{ uint8_t(h), uint8_t(h >> 8), uint8_t(h >> 16) }
							  : Rgb8{ uint8_t(h % 4 * 60), 90, 30 };
			if (h % 5 == 0) {
				raster[i].ink = uint8_t(1 + (h >> 24) % 3);
				raster[i].writeTick = uint16_t((h >> 32) % 100);
				raster[i].eraseTick = uint16_t((h >> 48) % 200);
			}
		}
		backdrop.pick(raster);
		for (uint16_t tick : { 0, 50, 150, 65534 }) {
			size_t inked = 0;
			for (int y = 0; y < height; ++y) {
				const uint32_t *words = backdrop.row(y);
				for (int x = 0; x < width; ++x) {
					const size_t k = size_t(y) * width + x;
					ASSERT_EQ(ColourBackdrop::onBoard(words[x]), texelOf[k] >= 0);
					Rgb8 want = direct(texelOf[k], staticColour[k], raster, tick);
					Rgb8 got = backdrop.colourAt(words[x], tick, inked);
					ASSERT_TRUE(got == want) << "pixel " << k;
				}
			}
		}
	}
}
