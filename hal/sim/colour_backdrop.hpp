// What each colour pixel shows behind the lecturer: off the board display
// the static colour of what the ray hits (wall, desk, a calibration target),
// on it the board texel it sees, picked from each cycle's raster.
//
// Memory (issue 15): a pixel is one 32-bit word, the colour and, on the
// board, the texel's ink, and the words are kept a row at a time in a
// RowPalette (row_palette.hpp: a row shows a few colours, so about a byte a
// pixel). Before it took 12 bytes: a whole BoardTexel each (8) and the
// grid's texel index (4). What a word cannot hold is kept only where it
// exists, in row-major order:
//  - the raster index each board pixel shows, as its step from the previous
//    board pixel's index (one byte: neighbouring pixels see neighbouring
//    texels; a step too long for a byte, once a row or so, escapes to the
//    whole index), read back only when a cycle's texels are picked;
//  - the ink's write and erase ticks, only for the inked pixels (2% of the
//    board), which colourAt() reads with a running count.
// The colours are the texels' own bits: a frame is the same as with the
// texels kept whole.
#pragma once

#include "hal/sim/lecture_script.hpp"
#include "hal/sim/row_palette.hpp"

#include <cstdint>
#include <vector>

namespace depthkey::sim {

class ColourBackdrop
{
public:
	// The colour grid's tables, one entry a pixel of a `width` wide picture
	// in row-major order: texelOf the raster index (-1 off the board),
	// staticColour the colour off the board. Board pixels show nothing until
	// pick().
	void build(int width, const std::vector<int32_t> &texelOf, const std::vector<Rgb8> &staticColour);
	// Each board pixel takes its texel of one cycle's raster.
	void pick(const std::vector<BoardTexel> &raster);

	// Row y's words, valid until another row is asked for.
	const uint32_t *row(int y) const { return words_.row(y); }
	static bool onBoard(uint32_t word) { return word & kBoard; }

	// A pixel's colour at `tick` (LectureScript ticks into the cycle), from
	// its word. Every pixel of a frame must be asked in row-major order,
	// `inked` starting at 0: it counts the inked pixels passed, whose ticks
	// are kept apart.
	Rgb8 colourAt(uint32_t word, uint16_t tick, size_t &inked) const
	{
		const uint32_t ink = (word >> kInkShift) & kInkMask;
		if (ink) {
			const uint32_t ticks = ticks_[inked++];
			if (tick >= (ticks & 0xFFFF) && tick < (ticks >> 16))
				return LectureScript::inkColours()[ink];
		}
		return { static_cast<uint8_t>(word), static_cast<uint8_t>(word >> 8), static_cast<uint8_t>(word >> 16) };
	}

private:
	static constexpr uint32_t kBoard = 1u << 31;
	static constexpr int kInkShift = 24;
	static constexpr uint32_t kInkMask = 0x7F;
	static constexpr uint8_t kEscape = 0; // a step of (-8, -8) texels: never taken as a step

	static uint32_t pack(Rgb8 c) { return c.r | uint32_t(c.g) << 8 | uint32_t(c.b) << 16; }

	int width_ = 0;
	RowPalette<uint32_t> words_;     // per pixel: kBoard, ink, colour
	std::vector<uint32_t> rowWords_; // a row of words being built
	std::vector<uint8_t> steps_;     // per board pixel: column step + 8 | (row step + 8) << 4
	std::vector<int32_t> escapes_;   // the whole index of each kEscape step
	std::vector<uint32_t> ticks_;    // per inked board pixel: writeTick | eraseTick << 16
};

} // namespace depthkey::sim
