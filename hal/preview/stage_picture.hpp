// How a stage image looks to a person (PNG snapshots, the preview page):
// colour as it is, depth in false colour (0.5 m .. 4 m, nearer warmer, no
// measurement black), seeds in three colours (lecturer orange, board blue,
// undecided grey), masks in grey. Drawn by the project itself: the daemon
// links no drawing library (issue 15).
#pragma once

#include "algo/stage_images.hpp"

#include <string>

namespace depthkey {

// RGB, or grey (masks): exactly one is non-empty, or neither for an empty stage.
struct StagePicture {
	RgbImage rgb;
	Gray8Image gray;

	bool empty() const { return rgb.empty() && gray.empty(); }
	int width() const { return rgb.empty() ? gray.width() : rgb.width(); }
	int height() const { return rgb.empty() ? gray.height() : rgb.height(); }
};

// Images narrower than 320 pixels (the ToF's) are enlarged 4x, nearest
// neighbour, so that a pixel stays a pixel.
StagePicture drawStagePicture(const StageImage &stage);

// A layer with straight alpha (the lecturer layer) over a grey checkerboard
// of kCheckerSquare-pixel squares, so that its transparency shows: each
// pixel is (colour * a + checker * (255 - a) + 127) / 255.
constexpr int kCheckerSquare = 16;
constexpr uint8_t kCheckerLight = 153, kCheckerDark = 102;
StagePicture drawLayerPicture(const RgbaImage &layer);

// As PNG; returns 0 or a negative errno with error set.
int writeStagePicturePng(const std::string &path, const StagePicture &picture, std::string &error);

} // namespace depthkey
