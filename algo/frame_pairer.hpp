// Soft synchronisation of two free-running cameras (Friedland et al.: the
// ToF camera and the webcam are not triggered together, their frames are
// paired by time). Depth frames are kept in a short history; each colour
// frame is paired with the depth frame whose corrected time (timestamp +
// offset, the depth camera's latency) is nearest, if it is within maxSkew
// (match), or with the depth frames just before and just after it in time
// (bracket: what a colour frame held back by pairing.delay_ms is keyed with,
// algo/pairing_queue.hpp).
//
// Drop policy (issue 29 point 4: no blink):
//  - a colour frame with no depth frame within maxSkew is still keyed, with
//    the nearest depth frame if that is within kLostNs (a second): the
//    bracket says how far off it is (staleNs), the pipeline grows the depth
//    superset by how far the lecturer can walk in that time, and the frame
//    goes out flagged DK_SHM_FLAG_DEPTH_STALE. Counted stale. A pairing
//    hiccup then costs a looser key, not a strobe of the board alone;
//  - only a colour frame with no depth frame within kLostNs (the depth
//    camera offline or silent for over a second) is not keyed (the daemon
//    publishes the board alone, marked offline) and counted unpaired;
//  - a depth frame may serve several colour frames (depth runs slower);
//  - a depth frame that leaves the history without ever being paired is
//    counted unused (depth faster than colour, or colour missing);
//  - a depth frame older than the newest one held is refused and counted
//    (it would pair wrongly); the history is cleared on a camera restart.
// Pure: times are handed in, nothing is read from a clock.
#pragma once

#include "algo/frames.hpp"

#include <array>
#include <cstdint>

namespace depthkey {

// The pairing.offset_ms values that can ever pair (issue 31 point 7), in ms.
// A colour frame captured at c is keyed by c + delay + one colour period
// (its transfer) at the latest, so it needs a depth frame stamped by then:
// corrected = depth + offset >= c - maxSkew gives offset >= -(delay + maxSkew
// + colour period). The pairer keeps kHistory depth frames (their span at the
// depth rate), so a depth frame older than that span before c is gone: offset
// <= history span + maxSkew. Outside, no frame is ever paired and the daemon
// never becomes ready.
struct PairableOffsets {
	int minMs = 0, maxMs = 0;
};
PairableOffsets pairableOffsetsMs(int maxSkewMs, int delayMs, int colourFps, int depthFps);

struct PairingStats {
	uint64_t paired = 0;
	uint64_t unpaired = 0;
	uint64_t stale = 0; // keyed with depth beyond maxSkew (kLostNs at most)
	uint64_t depthUnused = 0;
	uint64_t depthOutOfOrder = 0;
};

class FramePairer
{
public:
	// 6 frames: 600 ms at 10 fps, 100 ms at 60 fps; enough for a frame
	// before and one after a colour frame held back up to pairing.delay_ms.
	static constexpr size_t kHistory = 6;
	// Depth farther than this from a colour frame is lost, not late: the
	// lecturer may have walked anywhere since (issue 29 point 4).
	static constexpr int64_t kLostNs = 1'000'000'000;

	void configure(int64_t offsetNs, uint64_t maxSkewNs);
	void clear();

	void addDepth(const DepthFrame &frame);
	// The depth frame to key colourNs with, or nullptr. Valid until the next
	// addDepth/clear.
	const DepthFrame *match(uint64_t colourNs);

	// The depth frames whose corrected times are the latest at or before
	// colourNs and the earliest after it, each only within maxSkew (nullptr
	// otherwise); counted paired when either exists. When neither is, the
	// nearest depth frame within kLostNs, alone (before or after by its
	// time), with staleNs its distance from colourNs: counted stale. Valid
	// until the next addDepth/clear. beforeNs/afterNs receive the corrected
	// times.
	struct Bracket {
		const DepthFrame *before = nullptr, *after = nullptr;
		int64_t beforeNs = 0, afterNs = 0;
		// > 0: no depth within maxSkew; the time between the colour frame
		// and the depth frame it is keyed with (the lecturer moved since).
		int64_t staleNs = 0;
		bool any() const { return before || after; }
		bool stale() const { return staleNs > 0; }
	};
	Bracket bracket(uint64_t colourNs);

	// The newest depth frame, paired or not (snapshots); nullptr if none.
	const DepthFrame *newest() const;
	// Corrected time of the newest depth frame; false when there is none.
	bool newestNs(int64_t &ns) const;
	const PairingStats &stats() const { return stats_; }

private:
	struct Slot {
		DepthFrame frame;
		bool used = false;
	};
	int64_t corrected(const DepthFrame &frame) const;
	// bracket()'s fallback: the nearest depth frame within limitNs, stale.
	Bracket nearestWithin(int64_t colourNs, int64_t limitNs);

	std::array<Slot, kHistory> slots_;
	size_t count_ = 0;  // valid slots
	size_t next_ = 0;   // slot the next frame goes into
	int64_t offsetNs_ = 0;
	uint64_t maxSkewNs_ = 150'000'000;
	PairingStats stats_;
};

} // namespace depthkey
