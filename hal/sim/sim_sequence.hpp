// The simulated lecture as a sequence of what depthkeyd would receive,
// without an event loop: colour frame n at its capture time with its ground
// truth, paired with the newest depth frame stamped at or before it (the
// daemon's pairing rule), stamped latency after its true capture.
// For depthkey-eval, the tests and the recorder of test sequences.
#pragma once

#include "hal/sim/lecture_simulator.hpp"
#include "hal/sim/sim_timing.hpp"

namespace depthkey {

class SimSequence
{
public:
	void configure(const SimSettings &settings, int colourWidth, int colourHeight, int colourFps, int depthFps);

	// Renders colour frame n and its truth; depth is the paired depth frame
	// (re-rendered only when the pairing moves on). False when no depth
	// frame exists yet at that time (the first few colour frames).
	bool frame(uint64_t n, ColourFrame &colour, GroundTruth &truth, DepthFrame &depth);

	// True capture time of the depth frame last returned, s.
	double depthCaptureS() const { return depthCaptureS_; }
	LectureSimulator &simulator() { return simulator_; }
	const sim::SimTiming &timing() const { return timing_; }

private:
	LectureSimulator simulator_;
	sim::SimTiming timing_;
	DepthFrame depth_;
	int64_t depthIndex_ = -1;
	double depthCaptureS_ = 0;
};

} // namespace depthkey
