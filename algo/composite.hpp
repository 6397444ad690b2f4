// Paper Figure 1: the lecturer laid semi-transparently over the board.
//   composite = board * (1 - o*a) + lecturer * (o*a)
// with o the configured opacity and a the alpha matte (0..255). Fixed point:
// o is Q8 (256 = opaque), the blend weight w = round(o*a/255) is Q8 too.
#pragma once

#include "algo/image.hpp"

#include <cstdint>

namespace depthkey {

// 0..1 -> 0..256, rounded. Done once per config, not per pixel.
int opacityToQ8(double opacity);

// Reference row kernel (plain C++). out may alias neither input.
void compositeRow_C(const Rgb8 *lecturer, const uint8_t *alpha, const Rgb8 *board,
		    int opacityQ8, Rgb8 *out, int width);

// Straight (not premultiplied) alpha, as the recorder's RGBA layer expects.
void lecturerLayerRow_C(const Rgb8 *colour, const uint8_t *alpha, Rgba8 *out, int width);

// Whole images; outputs are resized to the colour image's size.
void composite(const RgbImage &lecturer, const Gray8Image &alpha, const RgbImage &board,
	       int opacityQ8, RgbImage &out);
void lecturerLayer(const RgbImage &colour, const Gray8Image &alpha, RgbaImage &out);

} // namespace depthkey
