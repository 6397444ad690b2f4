// The on-disk format of a recorded sequence (docs/sequences.md),
// in the manner of the TUM RGB-D benchmark, readable by common tools:
//
//   DIR/rgb.txt        "# timestamp filename" header, then one line a frame:
//   DIR/depth.txt      "<seconds with 9 decimals> <stream>/<sequence>.png"
//   DIR/amplitude.txt  (the same timestamps as depth.txt)
//   DIR/intensity.txt  (likewise, optional)
//   DIR/mask.txt       (ground truth, the same timestamps as rgb.txt, optional)
//   DIR/rgb/*.png        8-bit RGB
//   DIR/depth/*.png      16-bit grey, millimetres, 0 = no measurement
//   DIR/amplitude/*.png  16-bit grey, camera units
//   DIR/intensity/*.png  16-bit grey, camera units
//   DIR/mask/*.png       8-bit grey, lecturer coverage 0..255
//
// Timestamps are the frames' CLOCK_MONOTONIC capture times; nine decimals
// keep them exact to the nanosecond, so a replay is bit-exact.
#pragma once

#include <cstdint>
#include <string>

namespace depthkey::recording {

constexpr const char *kStreams[] = { "rgb", "depth", "amplitude", "intensity", "mask" };
enum Stream { Rgb, Depth, Amplitude, Intensity, Mask, StreamCount };

std::string formatTimestamp(uint64_t ns);             // "12.345678901"
bool parseTimestamp(const std::string &text, uint64_t &ns);
std::string frameFileName(Stream stream, uint64_t sequence); // "rgb/000042.png"

} // namespace depthkey::recording
