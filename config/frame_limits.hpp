// The largest images depthkey accepts anywhere: the config's limits for
// colour/depth width and height, and for a board image. Readers check an
// image file's header against these before decoding, so a 5 MB PNG that
// claims 20000x20000 pixels is refused instead of allocating 1.2 GB.
#pragma once

#include <cstddef>

namespace depthkey {

constexpr int kMaxFrameWidth = 1920;    // colour.width, depth.width
constexpr int kMaxFrameHeight = 1080;   // colour.height, depth.height
constexpr int kMaxBoardImageSide = 4096; // composite.board_image, scaled to the frame
// An image file's bytes: more than any PNG of the sizes above needs.
constexpr size_t kMaxImageFileBytes = 64u << 20;
// A sequence's index file (rgb.txt...): ~40 bytes a frame, so over a
// million frames, about 10 hours at 30 fps.
constexpr size_t kMaxIndexFileBytes = 64u << 20;

} // namespace depthkey
