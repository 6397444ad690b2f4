// The board as its own picture says it looks (issue 11): the electronic board
// delivers its content ([board]), and the board homography H says which board
// pixel each colour pixel sees. Where the display is seen, the camera's colour
// of the empty board is predicted from that picture: the board pixel under
// the colour pixel, times a gain per channel that carries the room light and
// the camera's response. The board model (algo/board_model.hpp) is taught the
// prediction every frame, so that it knows the board behind the lecturer, the
// strokes written beside his hand before they were ever seen, and the board
// that a wrong decision kept from being learned.
//
// Why (docs/accuracy.md, session 10): a board model that knew the empty board
// everywhere would meet the mean targets (0.971 / 0.910 against 0.966 /
// 0.887); taught this prediction (the simulator's true H) it scores 0.969 /
// 0.900, and 0.967 / 0.897 with H 1.5 colour px off.
//
// The gain is measured each frame where the colour already matches the board
// model within kFitDistance (board that is seen and learned): the sum of the
// colour over the sum of the picture, per channel, Q8. Without kMinFitPixels
// such pixels (no learned board on the display yet) nothing is predicted.
//
// The map from colour pixel to board pixel is computed once per H (nearest
// board pixel: the camera sees the display at about three board pixels a
// colour pixel). The picture is sampled through it once per picture (the
// board delivers 10 a second, the camera 25; the sampling's scattered reads
// of a 4.5 MB picture are most of the cost); per frame everything is
// integer, sequential and allocation-free.
#pragma once

#include "algo/board_model.hpp"
#include "algo/homography.hpp"
#include "algo/image.hpp"
#include "algo/radial_lens.hpp"

#include <cstdint>
#include <utility>
#include <vector>

namespace depthkey {

class BoardPicturePrior
{
public:
	static constexpr int kFitDistance = 30;     // L1, levels: "this pixel is board as learned"
	// The gain is a sum over the display: every 4th row measures it as well
	// (tens of thousands of pixels at 640x480) at a quarter of the cost.
	// Wider frames measure on a grid as sparse in columns as they are wider
	// (rounded: 2 from 960, 3 from 1600 pixels wide), rows the same, so the
	// pixels and the cost stay those of 640x480 (at 1920x1080 the fit was
	// 25 M instructions a frame on every 4th row, issue 28).
	static constexpr int kFitRowStride = 4;
	static constexpr size_t kMinFitPixels = 250; // measured, on those rows

	// A seen colour pixel is undistorted by the lens, then colourToBoard
	// maps it to a board picture pixel (u, v) of a boardWidth x boardHeight
	// picture (config/board_calibration_file.hpp). Returns -EINVAL for
	// empty sizes.
	int configure(int colourWidth, int colourHeight, const Homography &colourToBoard, const RadialLens &lens,
		      int boardWidth, int boardHeight);
	void clear()
	{
		boardOf_.clear();
		sampledFrom_ = nullptr;
	}
	// The picture's pixels changed in place: the next predict() samples it
	// again. A picture at another address is sampled again anyway.
	void pictureChanged() { sampledFrom_ = nullptr; }
	// Only the picture's rows firstRow..lastRow changed in place (the
	// others hold the same pixels): the next predict() samples again only
	// the colour rows that see one of them. firstRow > lastRow: nothing
	// changed. A board delivers 10 pictures a second, mostly the same
	// board with a stroke more; sampling a whole 1920x780 picture again is
	// 300k scattered reads (about a tenth of a keyed frame's time).
	void pictureRowsChanged(int firstRow, int lastRow);
	bool configured() const { return !boardOf_.empty(); }
	bool configuredFor(int colourWidth, int colourHeight) const
	{
		return configured() && colourWidth == colourWidth_ && colourHeight == colourHeight_;
	}

	// Measures the gain for this frame's picture; false (nothing to teach)
	// when the sizes differ from the configured ones or too few pixels were
	// there to measure it. The predicted empty board is then sampled() times
	// gainQ8() per channel (Q8, clamped at 255) where onDisplay() is
	// kTrimapBoard (0): BoardModel::teach() takes the three.
	bool predict(const RgbImage &picture, const RgbImage &colour, const BoardModel &model);

	const RgbImage &sampled() const { return sampled_; }
	const Gray8Image &onDisplay() const { return onDisplay_; }
	// The grid the gain is measured on.
	int fitRowStep() const { return kFitRowStride * fitScale_; }
	int fitColumnStep() const { return fitScale_; }
	const int *gainQ8() const { return gainQ8_; }
	// The prediction at one pixel, as teach() computes it (for tests).
	Rgb8 predictedAt(int x, int y) const { return BoardModel::scaleQ8(sampled_.row(y)[x], gainQ8_); }

private:
	void sampleRow(const RgbImage &picture, int y);

	int colourWidth_ = 0, colourHeight_ = 0, boardWidth_ = 0, boardHeight_ = 0;
	int fitScale_ = 1;
	std::vector<int32_t> boardOf_; // per colour pixel: board pixel index, -1 off the display
	RgbImage sampled_;             // the picture under each colour pixel (on the display)
	const RgbImage *sampledFrom_ = nullptr; // the picture sampled_ holds; null = sample again
	// Per colour row, the first and last picture row it sees (first > last:
	// none), and the picture rows changed since sampled_ was made.
	std::vector<std::pair<int, int>> pictureRowsOf_;
	int changedFirst_ = 1, changedLast_ = 0;
	Gray8Image onDisplay_;
	int gainQ8_[3] = { 256, 256, 256 };
};

} // namespace depthkey
