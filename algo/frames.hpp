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
	// What the frame shows, when something knows it: the lecturer's coverage
	// (0..255, lecturer where >= 128, as depthkey-eval scores it), filled by
	// the simulated camera and by a replay of a sequence with mask/ (issue
	// 29). Empty from a real camera: the daemon then scores nothing.
	Gray8Image truth;
	uint64_t timestampNs = 0; // capture time, CLOCK_MONOTONIC
	uint64_t sequence = 0;
};

} // namespace depthkey
