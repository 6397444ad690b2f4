// How a stage image looks to a person (PNG snapshots, the preview page):
// colour as it is, depth in false colour (0.5 m .. 4 m, nearer warmer, no
// measurement black), seeds in three colours (lecturer orange, board blue,
// undecided grey), masks in grey. Out is BGR (CV_8UC3) or grey (CV_8UC1).
#pragma once

#include "algo/stage_images.hpp"

#include <opencv2/core.hpp>

namespace depthkey {

// An empty Mat for an empty stage. Images narrower than 320 pixels (the
// ToF's) are enlarged 4x, nearest neighbour, so that a pixel stays a pixel.
cv::Mat drawStagePicture(const StageImage &stage);

} // namespace depthkey
