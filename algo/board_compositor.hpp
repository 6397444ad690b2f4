// The lecturer laid over the board's own picture in the board's geometry
// (the paper's Figure 1): the colour camera sees the board's display as a
// quadrilateral, the homography H (colour px -> board px) says where each
// camera pixel lands on the board, and the lecturer's colour and alpha are
// warped there and blended over the board picture with composite.opacity,
// the same blend as the camera-geometry composite (algo/composite.hpp).
//
// The warp is a per-board-pixel map, precomputed once per H and size: the
// colour-image point each board pixel shows, in Q8 fixed point, sampled
// bilinearly (colour and alpha each straight, as the camera-geometry
// composite takes the camera's pixel as it is). Only the board pixels the
// lecturer's ROI can reach are warped; elsewhere the composite is the board
// and the board-geometry lecturer layer is transparent. Nothing is allocated
// per frame (tests/board_compositor_test.cpp counts).
#pragma once

#include "algo/homography.hpp"
#include "algo/image.hpp"
#include "algo/trimap.hpp"

#include <cstdint>
#include <vector>

namespace depthkey {

class BoardCompositor
{
public:
	// colourToOutput maps colour pixels to pixels of the output (the board
	// picture at its output size). Allocates the map; false when H is
	// singular or a size is empty (the compositor is then unconfigured).
	bool configure(const Homography &colourToOutput, int colourWidth, int colourHeight, int outputWidth,
		       int outputHeight);
	void clear();
	bool configured() const { return outputWidth_ > 0; }
	int outputWidth() const { return outputWidth_; }
	int outputHeight() const { return outputHeight_; }

	// alpha is 0 outside roi (the pipeline's ROI). board must be the output
	// size. composite (RGB) and lecturer (RGBA, straight alpha) are resized
	// to the output size; lecturer is transparent outside the warped region.
	// Pass the same lecturer image every frame (see forgetLayer()).
	void compose(const RgbImage &colour, const Gray8Image &alpha, const Roi &roi, const RgbImage &board,
		     int opacityQ8, RgbImage &composite, RgbaImage &lecturer);

	// compose() clears only what it wrote into lecturer last time: call this
	// when lecturer was written by anyone else (the next compose clears all).
	void forgetLayer() { layerValid_ = false; }

	// The board pixels the last compose() warped (for tests and previews).
	const Roi &warpedRoi() const { return warped_; }
	// The colour point board pixel (x, y) shows, Q8; false when the camera
	// does not see that board pixel.
	bool sourceOf(int x, int y, int32_t &sxQ8, int32_t &syQ8) const;

	static constexpr int32_t kOutside = INT32_MIN;

private:
	Roi boardRoiOf(const Roi &colourRoi) const;
	void warpRow(const RgbImage &colour, const Gray8Image &alpha, const Rgb8 *board, int y, int x0, int x1,
		     int opacityQ8, Rgb8 *composite, Rgba8 *lecturer) const;

	Homography colourToOutput_;
	int colourWidth_ = 0, colourHeight_ = 0, outputWidth_ = 0, outputHeight_ = 0;
	std::vector<int32_t> mapX_, mapY_; // Q8 colour coordinates per output pixel, kOutside = unseen
	Roi warped_, cleared_;
	bool layerValid_ = false;          // lecturer is transparent outside cleared_
};

} // namespace depthkey
