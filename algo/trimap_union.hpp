// The trimap of a colour frame keyed with depth from both sides in time
// (algo/pairing_queue.hpp): the lecturer can be wherever either depth frame
// saw him, and is surely there only where both did. So, per pixel:
//   surely lecturer  where both trimaps say surely lecturer (the core);
//   surely board     where both say surely board;
//   undecided        everywhere else (the superset is the union), graded
//                    (algo/trimap.hpp) by the two labels blended by time:
//                    a colour frame near the later depth frame leans on it.
// Only the two ROIs are touched; out's previous ROI is cleared first.
#pragma once

#include "algo/seed_mapper.hpp"

namespace depthkey {

// a and b must have the same size; out is resized to it. laterQ8 (0..256)
// is how far the colour frame lies from a's capture towards b's.
void uniteTrimaps(const MappedSeeds &a, const MappedSeeds &b, int laterQ8, MappedSeeds &out);

} // namespace depthkey
