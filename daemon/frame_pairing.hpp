// Which depth frames go with each colour frame: the pairing queue that holds
// colour frames until depth from both sides of them has come
// (pairing.delay_ms), and the depth camera's offset, measured once a second
// by correlating motion (algo/latency_estimator.hpp): applied when
// pairing.offset_ms is "auto", logged when it moved by 5 ms or more.
#pragma once

#include "algo/frames.hpp"
#include "algo/latency_estimator.hpp"
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

private:
	int64_t offsetNs() const;

	PairingSettings settings_;
	PairingQueue queue_;
	LatencyEstimator latency_;
	LatencyEstimator::Estimate estimate_;
	double loggedMs_ = 1e9;
};

} // namespace depthkey
