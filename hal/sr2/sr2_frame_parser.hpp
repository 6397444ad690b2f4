// SR-2 raw transfer -> DepthFrame, and the auto integration time rule. Pure
// functions: the USB backend hands in bytes, tests hand in crafted frames.
#pragma once

#include "algo/frames.hpp"

#include <cstddef>
#include <cstdint>

namespace depthkey {

enum class Sr2FrameCheck {
	Ok,
	Short,      // fewer bytes than three images: the transfer was cut
	TooLong,    // more than one rounded read: out of step with the camera
	Saturated,  // too many 0xFFFF distance words
	Flat,       // a constant distance image: stuck sensor or filler
};

const char *sr2FrameCheckName(Sr2FrameCheck check);

struct Sr2FrameStats {
	uint32_t meanIntensity = 0;
};

// Validates the whole transfer first and only then converts, so a refused
// frame leaves out untouched (the last good frame stays usable). Distance in
// mm outside [minMm, maxMm] becomes 0 (no measurement). Allocation-free once
// out has the SR-2's size.
Sr2FrameCheck parseSr2Frame(const uint8_t *data, size_t length, int minMm, int maxMm,
			    DepthFrame &out, Sr2FrameStats &stats);

// The next integration time (register 0x09, 0..255) that moves the mean
// intensity into [low, high]; unchanged inside the window.
int sr2NextIntegrationTime(int current, uint32_t meanIntensity, int low, int high);

} // namespace depthkey
