// Trimap labels, as GIMP's foreground select writes them: 0 = surely board
// (background), 255 = surely lecturer (foreground), anything else undecided.
// The depth seeds, depthkey-siox's input and SIOX's refinement all use them.
#pragma once

#include <cstdint>

namespace depthkey {

constexpr uint8_t kTrimapBoard = 0;
constexpr uint8_t kTrimapUndecided = 128;
constexpr uint8_t kTrimapLecturer = 255;

// A rectangle of pixels [x0, x1) x [y0, y1); empty when x0 >= x1 or y0 >= y1.
struct Roi {
	int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
	bool empty() const { return x0 >= x1 || y0 >= y1; }
	bool operator==(const Roi &) const = default;
};

} // namespace depthkey
