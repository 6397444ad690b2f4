#include "algo/composite.hpp"

#include <cmath>

namespace depthkey {

int opacityToQ8(double opacity)
{
	if (!(opacity > 0.0))
		return 0;
	if (opacity >= 1.0)
		return 256;
	return static_cast<int>(std::lround(opacity * 256.0));
}

void compositeRow_C(const Rgb8 *lecturer, const uint8_t *alpha, const Rgb8 *board,
		    int opacityQ8, Rgb8 *out, int width)
{
	for (int x = 0; x < width; ++x) {
		// p = o*a <= 256*255 = 65280; round(p/255) without a division:
		// (p + 128 + ((p + 128) >> 8)) >> 8 is exact for 0 <= p < 65536.
		unsigned p = static_cast<unsigned>(opacityQ8) * alpha[x] + 128u;
		unsigned w = (p + (p >> 8)) >> 8;  // 0..256
		unsigned wb = 256u - w;
		out[x].r = static_cast<uint8_t>((board[x].r * wb + lecturer[x].r * w + 128u) >> 8);
		out[x].g = static_cast<uint8_t>((board[x].g * wb + lecturer[x].g * w + 128u) >> 8);
		out[x].b = static_cast<uint8_t>((board[x].b * wb + lecturer[x].b * w + 128u) >> 8);
	}
}

void lecturerLayerRow_C(const Rgb8 *colour, const uint8_t *alpha, Rgba8 *out, int width)
{
	for (int x = 0; x < width; ++x)
		out[x] = { colour[x].r, colour[x].g, colour[x].b, alpha[x] };
}

void composite(const RgbImage &lecturer, const Gray8Image &alpha, const RgbImage &board,
	       int opacityQ8, RgbImage &out)
{
	out.resize(lecturer.width(), lecturer.height());
	for (int y = 0; y < lecturer.height(); ++y)
		compositeRow_C(lecturer.row(y), alpha.row(y), board.row(y), opacityQ8, out.row(y),
			       lecturer.width());
}

void lecturerLayer(const RgbImage &colour, const Gray8Image &alpha, RgbaImage &out)
{
	out.resize(colour.width(), colour.height());
	for (int y = 0; y < colour.height(); ++y)
		lecturerLayerRow_C(colour.row(y), alpha.row(y), out.row(y), colour.width());
}

} // namespace depthkey
