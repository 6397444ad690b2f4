// The depth of what never moves (board, wall, desk, monitor), per ToF pixel,
// so that depth seeding can tell the lecturer from furniture standing in his
// depth interval (the paper's Figure 7: a desk in front of the board is as
// near as the lecturer, and may be the larger in-range area).
//
// A running mean and mean absolute deviation of the depth per pixel (the
// usual background model, here of depth): a pixel is "moving" where its
// depth lies in front of the mean by more than kToleranceMm plus twice the
// deviation (so a noisy pixel, the glossy monitor's weak echo, does not
// count as moving), or where the mean of its 3x3 box lies in front of the
// box's means by kToleranceMm plus twice the box's deviation over sqrt(n)
// (the noise of a mean of n pixels): at the ToF's noisy image edge an arm
// reaching in is nearer than one pixel's threshold, and only the box sees
// it. Moving pixels do not update the mean; instead the mean
// fades towards them by kFadeMmPerFrame, so a lecturer standing still is
// taken for background only after tens of seconds, and a desk put into the
// room is learned after a while.
//
// Two uint16 per ToF pixel (Q3 mm) and the frame's int32 excess over the
// mean, integer arithmetic, no allocation once sized.
#pragma once

#include "algo/image.hpp"

#include <cstdint>
#include <vector>

namespace depthkey {

class StaticBackground
{
public:
	// Farther than the ToF noise on the board (a few cm at the image
	// centre, sigma), nearer than a lecturer stands from anything behind him
	// (450 mm and more from the board in the simulated lecture).
	static constexpr int kToleranceMm = 150;
	// 25 mm a second at 25 depth frames a second.
	static constexpr int kFadeMmPerFrame = 1;
	// Mean and deviation follow a static pixel with weight 1/16 (about 16
	// frames): a single noisy depth cannot move them far.
	static constexpr int kRateShift = 4;
	static constexpr int kFractionBits = 3; // Q3 mm: 7500 mm * 8 fits in uint16

	// Updates the model with a frame (0 = no measurement: unchanged) and
	// writes moving (255 where the depth is in front of the background and
	// so are at least two of the 4 neighbours, else 0: the noise of a weak
	// echo, a glossy monitor, makes scattered single pixels look moving;
	// a moving arm two pixels thick still counts). The first frame, or one of a new size, starts the model
	// with its depths and a deviation of kToleranceMm.
	void update(const Gray16Image &depthMm, Gray8Image &moving);
	// The learned depth of pixel i, mm (0 = not seen yet): the board's
	// depth behind the lecturer, for DepthSeeder::depthEvidence.
	int meanMm(size_t i) const { return i < mean_.size() ? mean_.data()[i] >> kFractionBits : 0; }

private:
	// pooled_: whether the 3x3 box around each measured pixel lies in front
	// of its means by more than kToleranceMm plus twice the deviation of
	// the box's mean noise (boxes of under 4 measured pixels: no).
	void poolBoxes(int w, int h);

	Gray16Image mean_, deviation_; // Q3 mm; mean 0 = not seen yet
	Gray8Image inFront_, pooled_;
	std::vector<int32_t> excess_; // this frame's depth in front of the mean, Q3 mm
	// poolBoxes' sums over each pixel's row of three: capped excess,
	// deviation, measured pixels.
	std::vector<int32_t> rowExcess_, rowDeviation_;
	std::vector<uint8_t> rowCount_;
};

} // namespace depthkey
