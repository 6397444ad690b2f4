// Where a recording session goes when its folder holds frames of an earlier
// boot. Timestamps are CLOCK_MONOTONIC, which starts again at a reboot: a
// classroom box switched off overnight would append frames stamped earlier
// than the ones already listed, and the reader refuses an index whose time
// goes backwards. So such a session goes into a folder of its own inside
// (DIR/boot-2, DIR/boot-3, ...), each a complete sequence folder, and the
// earlier recording stays as it was. Likewise a session whose colour frames
// are of another size than the folder's (issue 31): a replay plays one size.
#pragma once

#include <cstdint>
#include <string>

namespace depthkey {

// The latest timestamp the index files of dir list, 0 for none. Reads only
// each index's tail, so a long recording costs no more than a short one.
uint64_t lastRecordedNs(const std::string &dir);

// dir when its frames (if any) are no later than nowNs (CLOCK_MONOTONIC),
// else the first dir/boot-N, N = 2, 3, ..., that does not exist yet or whose
// frames are no later than nowNs: the folder of this boot's earlier runs.
// With a colour size, a dir whose colour frames are of another size (a
// reload changed [colour]) is left too: the session goes into dir/WxH (the
// same rules within), so that each folder replays at one [colour] size.
std::string sessionFolder(const std::string &dir, uint64_t nowNs, int colourWidth = 0, int colourHeight = 0);

} // namespace depthkey
