// The composite stream at a constant rate in capture time (issue 29 point
// 5): a recorder, a virtual webcam or a player that assumes the frame rate
// must see one frame per colour frame interval, or a recording plays fast
// wherever frames were shed (the keying worker behind) or keyed late. The
// slots between two published frames' capture times that went without one
// are filled with the previous output again, flagged repeated.
// Pure: times are handed in.
#pragma once

#include <cstdint>

namespace depthkey {

// How many capture slots of intervalNs lie strictly between the frames
// captured at previousNs and nowNs (rounded: a camera's capture times
// jitter), 0 when none or when the gap is longer than maxGapNs: an outage,
// not a hiccup (NO SIGNAL frames, not copies, cover it).
constexpr uint64_t skippedCaptureSlots(uint64_t previousNs, uint64_t nowNs, uint64_t intervalNs,
				       uint64_t maxGapNs)
{
	if (previousNs == 0 || nowNs <= previousNs || intervalNs == 0 || nowNs - previousNs > maxGapNs)
		return 0;
	const uint64_t slots = (nowNs - previousNs + intervalNs / 2) / intervalNs;
	return slots > 1 ? slots - 1 : 0;
}

} // namespace depthkey
