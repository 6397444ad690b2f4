// When the simulated cameras capture: the colour camera free-runs at its
// rate with jitter; the ToF camera free-runs at its own, with jitter, and
// stamps each frame when it reaches the host, depthLatencyMs after the true
// capture (the middle of its exposure). A consumer that pairs each colour
// frame with the latest depth frame (as depthkeyd does) therefore pairs
// pictures taken 40..150 ms apart: on a hand moving 1 m/s at 1.3 m that is
// the paper's 10-50 px offset.
#pragma once

#include "settings/settings.hpp"

#include <cstdint>

namespace depthkey::sim {

class SimTiming
{
public:
	void configure(const SimSettings &settings, int colourFps, int depthFps);

	double colourTime(uint64_t n) const;    // capture time of colour frame n (= its timestamp), s
	// The live colour camera (hal/sim/sim_cameras.hpp) delivers frame n on
	// its timer's tick: how long before that it was captured, s, in
	// [0, 2 * jitter]. The capture instants are colourTime's, the
	// deliveries on the period after them, so no frame comes before it is
	// taken.
	double colourCaptureDelay(uint64_t n) const;
	double depthCapture(uint64_t m) const;  // true capture time of depth frame m, s
	double depthStamp(uint64_t m) const;    // its timestamp: capture + latency, s
	// The newest depth frame stamped at or before timeS, or -1.
	int64_t latestDepthAt(double timeS) const;

	// The jitter of frame n of a stream in [-1, 1) (same seed, same jitter).
	double jitterUnit(uint64_t stream, uint64_t n) const;

private:
	uint64_t seed_ = 1;
	double colourPeriod_ = 0.04, depthPeriod_ = 0.1;
	double colourJitter_ = 0, depthJitter_ = 0, latency_ = 0;
};

} // namespace depthkey::sim
