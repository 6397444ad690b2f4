// Which depth frames go with each colour frame: the pairing queue that holds
// colour frames until depth from both sides of them has come
// (pairing.delay_ms), and the depth camera's offset, measured once a second
// by correlating motion (algo/latency_estimator.hpp): when pairing.offset_ms
// is "auto", applied once it deserves trust (algo/offset_gate.hpp), taken
// back when it makes pairing worse; the journal says when the applied offset
// or the reason for holding one changes.
#pragma once

#include "algo/frames.hpp"
#include "algo/latency_estimator.hpp"
#include "algo/offset_gate.hpp"
#include "algo/pairing_queue.hpp"
#include "settings/settings.hpp"

#include <cstdint>
#include <string>

namespace depthkey {

class FramePairing
{
public:
	// At start and on every reload.
	void configure(const Settings &settings);

	// arrivalNs: the loop's clock when the frame came.
	void addColour(const ColourFrame &frame, uint64_t arrivalNs)
	{
		latency_.addColour(frame.rgb, frame.timestampNs);
		queue_.addColour(frame, arrivalNs);
	}
	void addDepth(const DepthFrame &frame)
	{
		queue_.addDepth(frame); // same-size copy: no allocation after the first
		latency_.addDepth(frame, frame.timestampNs);
	}
	void clear() { queue_.clear(); }
	// Depth was lost: the offset is measured afresh from the frames after.
	void forgetLatency()
	{
		latency_.reset();
		estimate_ = {};
	}

	// Once a second; depthName names the camera in the journal.
	void updateLatency(const std::string &depthName);
	// Whether the newest depth frame is younger than half a second: depth
	// counts as delivering (DEPTH_OK on NO SIGNAL frames).
	bool depthFresh(uint64_t nowNs) const;

	PairingQueue &queue() { return queue_; }
	const PairingQueue &queue() const { return queue_; }
	const LatencyEstimator::Estimate &latency() const { return estimate_; }
	const OffsetGate &offsetGate() const { return gate_; }
	// For the status line and status.json: "measured -41 ms, applied -40 ms",
	// "measured -215 ms, none applied, held: WHY", or with a set offset_ms,
	// "set -40 ms (measured -41 ms)".
	std::string offsetStatus() const;

private:
	int64_t offsetNs() const;

	PairingSettings settings_;
	PairingQueue queue_;
	LatencyEstimator latency_;
	LatencyEstimator::Estimate estimate_;
	OffsetGate gate_;
	std::string logged_; // the last offset line journaled
};

} // namespace depthkey
