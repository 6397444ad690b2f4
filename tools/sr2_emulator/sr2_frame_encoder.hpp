// What an SR-2 sends for one frame request in output mode 0xC0: distance,
// intensity and amplitude as three little-endian u16 160x124 images, made
// from a simulated DepthFrame; and the broken transfers a failing camera or
// cable produces, for fault injection.
#pragma once

#include "algo/frames.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace depthkey {

enum class Sr2FrameFault {
	None,
	Short,   // the transfer ends early (about half a frame)
	Corrupt, // right length, garbage words (half of the distances saturated)
	Flat,    // right length, a constant filler word in every pixel
};

const char *sr2FrameFaultName(Sr2FrameFault fault);

// Encodes frame (160x124) into raw and returns how many bytes of raw to send:
// the whole frame, or fewer for Sr2FrameFault::Short. seed varies the garbage.
size_t encodeSr2Frame(const DepthFrame &frame, Sr2FrameFault fault, uint64_t seed,
		      std::vector<uint8_t> &raw);

} // namespace depthkey
