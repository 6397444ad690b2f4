// A bitmap font for the pictures the daemon draws itself (the NO SIGNAL
// frame), so that it needs no drawing library: printable ASCII, 16 x 18
// cells, 1 bit a pixel, each glyph with its advance. The glyphs are the
// Hershey Simplex font (public domain) as OpenCV's putText drew it at scale
// 0.5, thickness 1, thresholded: the same letters the frame had when OpenCV
// drew it, now blocky when enlarged.
#pragma once

#include <cstdint>

namespace depthkey {

struct Glyph {
	uint8_t advance;     // pixels to the next glyph's origin
	uint16_t rows[18];   // top row first; bit 15 is the leftmost pixel
};

constexpr int kGlyphWidth = 16, kGlyphHeight = 18;
constexpr int kGlyphBaseline = 13; // row of the baseline from the cell's top

// The glyph of c: printable ASCII, anything else a '?'.
const Glyph &glyphOf(char c);

} // namespace depthkey
