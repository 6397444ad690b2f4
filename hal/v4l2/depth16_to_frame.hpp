// 16-bit depth images (V4L2 Z16, or Y16 from cameras that send depth as plain
// grey) -> DepthFrame in millimetres. The scale (mm per count) is a Q16 fixed
// point factor made once from the config; values outside [minMm, maxMm] and
// raw 0 become 0 (no measurement). No allocation once out has the size.
#pragma once

#include "algo/frames.hpp"

#include <cstddef>
#include <cstdint>

namespace depthkey {

// Q16 scale from mm per count (0.01..100): round(mmPerCount * 65536).
uint32_t depthScaleQ16(double mmPerCount);

// One row: little-endian u16 counts -> mm.
void depth16ToMmRow(const uint8_t *src, uint16_t *mm, int width, uint32_t scaleQ16,
		    int minMm, int maxMm);

// A V4L2 depth camera measures no amplitude or intensity: amplitude is set to
// 65535 (fully trusted) where depth is valid and 0 where not, intensity to 0,
// so later stages that weigh by amplitude see exactly the valid pixels.
int depth16ToFrame(const uint8_t *data, size_t bytes, int width, int height,
		   size_t bytesPerLine, uint32_t scaleQ16, int minMm, int maxMm, DepthFrame &out);

} // namespace depthkey
