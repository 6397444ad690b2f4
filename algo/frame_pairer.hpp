// Soft synchronisation of two free-running cameras (Friedland et al.: the
// ToF camera and the webcam are not triggered together, their frames are
// paired by time). Depth frames are kept in a short history; each colour
// frame is paired with the depth frame whose corrected time (timestamp +
// offset, the depth camera's latency) is nearest, if it is within maxSkew
// (match), or with the depth frames just before and just after it in time
// (bracket: what a colour frame held back by pairing.delay_ms is keyed with,
// algo/pairing_queue.hpp).
//
// Drop policy:
//  - a colour frame with no depth frame within maxSkew is not keyed (the
//    daemon publishes it unkeyed, marked offline) and counted unpaired;
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
	uint64_t depthUnused = 0;
	uint64_t depthOutOfOrder = 0;
};

class FramePairer
{
public:
	// 6 frames: 600 ms at 10 fps, 100 ms at 60 fps; enough for a frame
	// before and one after a colour frame held back up to pairing.delay_ms.
	static constexpr size_t kHistory = 6;

	void configure(int64_t offsetNs, uint64_t maxSkewNs);
	void clear();

	void addDepth(const DepthFrame &frame);
	// The depth frame to key colourNs with, or nullptr. Valid until the next
	// addDepth/clear.
	const DepthFrame *match(uint64_t colourNs);

	// The depth frames whose corrected times are the latest at or before
	// colourNs and the earliest after it, each only within maxSkew (nullptr
	// otherwise); counted paired when either exists. Valid until the next
	// addDepth/clear. beforeNs/afterNs receive their corrected times.
	struct Bracket {
		const DepthFrame *before = nullptr, *after = nullptr;
		int64_t beforeNs = 0, afterNs = 0;
		bool any() const { return before || after; }
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

	std::array<Slot, kHistory> slots_;
	size_t count_ = 0;  // valid slots
	size_t next_ = 0;   // slot the next frame goes into
	int64_t offsetNs_ = 0;
	uint64_t maxSkewNs_ = 150'000'000;
	PairingStats stats_;
};

} // namespace depthkey
