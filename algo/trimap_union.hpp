// The trimap of a colour frame keyed with depth from both sides in time
// (algo/pairing_queue.hpp): the lecturer can be wherever either depth frame
// saw him, and is surely there only where both did. So, per pixel:
//   surely lecturer  where both trimaps say surely lecturer (the core);
//   surely board     where both say surely board;
//   undecided        everywhere else (the superset is the union), graded
//                    (algo/trimap.hpp) by the two labels blended by time:
//                    a colour frame near the later depth frame leans on it.
// The depth evidence (DepthSeeder::evidence) is blended by time too, except
// where an edge moved between the two captures: a blend of "lecturer" and
// "board" across the whole swept run says neither, while the lecturer's
// edge really lies at one point of it. Along each row, a run where the two
// frames surely disagree, with the lecturer on one side in both, is split
// where the edge is at the colour frame's time (moving at constant speed):
// his side takes the more lecturer-like evidence of the two, the rest the
// more board-like (the lecturer walks: rows follow him; a column pass as
// well was measured worse). Measured on the clean depth camera: BF 0.888 ->
// 0.907.
// Only the two ROIs are touched; out's previous ROI is cleared first.
#pragma once

#include "algo/seed_mapper.hpp"

namespace depthkey {

// a and b must have the same size; out is resized to it. laterQ8 (0..256)
// is how far the colour frame lies from a's capture towards b's.
void uniteTrimaps(const MappedSeeds &a, const MappedSeeds &b, int laterQ8, MappedSeeds &out);

// The edge-following part, one row [x0, x1) of the two evidences a and b
// (out holds their blend and is changed in swept runs only).
void interpolateEdgesInRow(const uint8_t *a, const uint8_t *b, int x0, int x1, int laterQ8, uint8_t *out);

} // namespace depthkey
