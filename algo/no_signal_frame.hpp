// The frame published while the colour camera is missing, so that the
// recorder never starves and the viewer sees why the picture is gone.
#pragma once

#include "algo/image.hpp"

#include <string>

namespace depthkey {

// Renders grey bars and the text (e.g. "NO SIGNAL: colour camera") into out,
// at out's size (the text on several lines where one is too wide). Called once
// per size/reason, not per frame.
void renderNoSignalFrame(const std::string &text, RgbImage &out);

} // namespace depthkey
