// What the cameras deliver to the pipeline, already converted from their
// device formats (YUYV, SR-2 raw words, Z16) by hal/.
#pragma once

#include "algo/image.hpp"

#include <cstdint>

namespace depthkey {

// A time-of-flight frame: distance, plus the amplitude and intensity images
// that say how far each distance can be trusted.
struct DepthFrame {
	Gray16Image depthMm;    // 0 = no measurement
	Gray16Image amplitude;  // modulation amplitude, camera units
	Gray16Image intensity;  // mean received light, camera units
	uint64_t timestampNs = 0; // capture time, CLOCK_MONOTONIC
	uint64_t sequence = 0;
};

struct ColourFrame {
	RgbImage rgb;
	uint64_t timestampNs = 0; // capture time, CLOCK_MONOTONIC
	uint64_t sequence = 0;
};

} // namespace depthkey
