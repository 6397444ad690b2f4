// Trimap labels, as GIMP's foreground select writes them: 0 = surely board
// (background), 255 = surely lecturer (foreground), anything else undecided.
// The depth seeds, depthkey-siox's input and SIOX's refinement all use them.
#pragma once

#include <cstdint>

namespace depthkey {

constexpr uint8_t kTrimapBoard = 0;
constexpr uint8_t kTrimapUndecided = 128;
constexpr uint8_t kTrimapLecturer = 255;

// The pipeline's depth trimap grades the undecided labels by what depth says
// (algo/depth_seeder.hpp), so that the decision can weigh it
// (algo/fused_evidence.hpp); everything strictly between board and lecturer
// is still undecided for SIOX:
//   kTrimapLecturer  the core: deep inside the lecturer's in-range area,
//                    fixed as lecturer;
//   kTrimapSubset    inside the eroded in-range area: where lecturer colours
//                    are learned, decided with a strong depth prior;
//   kTrimapInRange   in range at the area's edge;
//   kTrimapUndecided out of range, inside the superset (the dilation);
//   kTrimapBoard     outside the superset.
// Two depth frames around a colour frame are blended by time
// (algo/trimap_union.hpp), so any value in between occurs too.
constexpr uint8_t kTrimapSubset = 224;
constexpr uint8_t kTrimapInRange = 176;

// A rectangle of pixels [x0, x1) x [y0, y1); empty when x0 >= x1 or y0 >= y1.
struct Roi {
	int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
	bool empty() const { return x0 >= x1 || y0 >= y1; }
	bool operator==(const Roi &) const = default;
};

} // namespace depthkey
