// Furniture in the lecturer's depth interval (the paper's Figure 7: a desk
// and a monitor as near as he is), learned so that depth seeding can cut it
// off him when he stands next to or behind it. The lecturer picker
// (algo/lecturer_picker.hpp) chooses whole 4-connected in-range areas: once
// he touches the desk in the depth image, the desk is part of his area, and
// the keyer keys it in beside him (issue 29 section 6, simulated lecture
// seeds 1-3 from 19.5 s, where he writes behind the desk: IoU 0.45).
//
// A ToF pixel is furniture once it has been in range, still (not in front of
// the static background, algo/static_background.hpp) and outside the
// lecturer's in-range area of the previous frame for kFramesToLearn depth
// frames in a row (frames where it is in his area neither count nor clear).
// Anything in front of it (he walks in front of the desk: moving there) or a
// frame out of range clears it at once: the board's noise at the ToF's image
// edge, now and then in range, is never learned, so an arm reaching in there
// is not cut off. A lecturer who stands still is not learned: he is the
// lecturer chosen, and his pixels do not count.
//
// One uint8 counter per ToF pixel, no allocation once sized.
#pragma once

#include "algo/image.hpp"

#include <cstdint>

namespace depthkey {

class FurnitureMask
{
public:
	// 3 s at the SR-2's 10 frames a second: the lecturer passes by in less
	// (his edge pixels are briefly outside the previous, eroded lecturer),
	// a desk stands there for the whole lecture.
	static constexpr uint8_t kFramesToLearn = 30;

	// One depth frame: inRange, moving and previousLecturer (may be empty:
	// none yet) all the ToF frame's size. A new size starts afresh.
	void update(const Gray8Image &inRange, const Gray8Image &moving, const Gray8Image &previousLecturer);
	// Sets the furniture's non-zero pixels of image (the same size; else
	// unchanged) to value: 0 in the in-range mask; surely board in depth's
	// evidence (0 outside the superset stays 0).
	void fill(Gray8Image &image, uint8_t value) const;
	bool isFurniture(int x, int y) const
	{
		return x >= 0 && y >= 0 && x < stillFrames_.width() && y < stillFrames_.height() &&
		       stillFrames_.at(x, y) >= kFramesToLearn;
	}

private:
	Gray8Image stillFrames_;
};

} // namespace depthkey
