// The trimap of a colour frame keyed with depth from both sides in time
// (algo/pairing_queue.hpp): the lecturer can be wherever either depth frame
// saw him, and is surely there only where both did. So, per pixel:
//   surely lecturer  where both trimaps say surely lecturer (the core);
//   surely board     where both say surely board;
//   undecided        everywhere else (the superset is the union).
// Only the two ROIs are touched; out's previous ROI is cleared first.
#pragma once

#include "algo/seed_mapper.hpp"

namespace depthkey {

// a and b must have the same size; out is resized to it.
void uniteTrimaps(const MappedSeeds &a, const MappedSeeds &b, MappedSeeds &out);

} // namespace depthkey
