// Which in-range area of the depth image is the lecturer (paper 6.1 keeps
// the biggest; a desk or monitor in the lecturer's depth interval may be
// bigger, the paper's Figure 7). Each 4-connected component of the in-range
// mask is scored by
//   2 x its pixels in front of the static background (he moves, furniture
//       does not; algo/static_background.hpp), plus
//   its overlap with the lecturer last chosen (he is where he was a tenth
//       of a second ago, also when standing still so long that the
//       background model has taken him in).
// A component is a candidate only if it overlaps the previous lecturer or
// enough of it moves (a few noisy pixels on a glossy monitor do not make it
// a lecturer); with no candidate there is no lecturer (he has left). Before
// any lecturer was ever chosen, the biggest is taken, as in the paper: the
// very first frame has no history. That guess is only kept (by overlap)
// until something moves; the overlap counts fully once the one followed
// has moved (a lecturer, not a desk seen in an empty room at start-up).
#pragma once

#include "algo/image.hpp"
#include "algo/morphology.hpp"

namespace depthkey {

class LecturerPicker
{
public:
	// Keeps the chosen component of mask (in place, 255; all 0 when none)
	// and returns its size. moving is the same size as mask.
	int pick(Gray8Image &mask, const Gray8Image &moving, ComponentScratch &scratch);
	// The lecturer of this frame (the mask the last pick kept), for the
	// next frame.
	void remember(const Gray8Image &subset);
	// Whether the last pick's choice moves.
	bool lastMoved() const { return lastMoved_; }
	void reset();

	// Moving pixels that make a component a candidate: this many, and at
	// least 1/kMovingShareDivisor of it.
	static constexpr int kMinMovingPixels = 12;
	static constexpr int kMovingShareDivisor = 20;

private:
	Gray8Image previous_;
	bool everChosen_ = false;
	bool confirmed_ = false;   // the one followed has moved at some time
	bool lastChosen_ = false;  // the last pick kept a component
	bool lastMoved_ = false;   // the last pick's choice moves
};

} // namespace depthkey
