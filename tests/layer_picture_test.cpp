// The preview's lecturer tile (hal/preview/stage_picture.hpp): a layer with
// straight alpha over the grey checkerboard, in integers, against the same
// blend in floating point. Tolerance: 1 level (rounding of (c*a + k*(255-a))/255).
#include "hal/preview/stage_picture.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

using namespace depthkey;

TEST(LayerPicture, BlendsOverTheCheckerboardAsFloatingPointDoes)
{
	RgbaImage layer(70, 40);
	for (int y = 0; y < layer.height(); y++)
		for (int x = 0; x < layer.width(); x++)
			layer.at(x, y) = Rgba8{ uint8_t(x * 3), uint8_t(255 - y * 5), uint8_t((x * y) & 255),
						uint8_t((x * 37 + y * 11) & 255) };
	layer.at(0, 0).a = 0;   // transparent: the light square
	layer.at(16, 0).a = 0;  // the next square: dark
	layer.at(1, 0).a = 255; // opaque: the layer's colour

	const StagePicture picture = drawLayerPicture(layer);
	ASSERT_EQ(picture.width(), 70);
	ASSERT_EQ(picture.height(), 40);
	int worst = 0;
	for (int y = 0; y < layer.height(); y++)
		for (int x = 0; x < layer.width(); x++) {
			const Rgba8 p = layer.at(x, y);
			const double a = p.a / 255.0;
			const double k = ((x / kCheckerSquare + y / kCheckerSquare) % 2) ? kCheckerDark : kCheckerLight;
			const Rgb8 got = picture.rgb.at(x, y);
			const uint8_t channels[3][2] = { { p.r, got.r }, { p.g, got.g }, { p.b, got.b } };
			for (const auto &c : channels)
				worst = std::max(worst, std::abs(int(std::lround(c[0] * a + k * (1 - a))) - int(c[1])));
		}
	EXPECT_LE(worst, 1);
	EXPECT_EQ(picture.rgb.at(0, 0), (Rgb8{ kCheckerLight, kCheckerLight, kCheckerLight }));
	EXPECT_EQ(picture.rgb.at(16, 0), (Rgb8{ kCheckerDark, kCheckerDark, kCheckerDark }));
	EXPECT_EQ(picture.rgb.at(1, 0), (Rgb8{ 3, 255, 0 }));
}
