// The preview page at "/": one self-contained HTML document (no external
// scripts, styles or fonts: the box has no internet) showing every stage's
// MJPEG stream and the status from /status.json, refreshed each second.
#pragma once

#include <string_view>

namespace depthkey {

std::string_view previewPageHtml();

} // namespace depthkey
