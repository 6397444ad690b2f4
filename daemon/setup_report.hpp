// depthkeyd --check-config's second half (issue 30, the first-run path): the
// box's setup state as a technician checks it from the shell: which cameras
// the config names, whether the depth and the board are calibrated, and the
// next command when not.
#pragma once

#include "settings/settings.hpp"

#include <string>

namespace depthkey {

// Lines "colour camera: ...", "depth camera: ...", "depth calibration: ...",
// "board: ...", each ending in "\n". Reads the calibration files named.
std::string describeSetup(const Settings &settings);

} // namespace depthkey
