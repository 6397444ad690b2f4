// The simulated lecture as the stream depthkeyd would receive, without an
// event loop: colour frame n at its capture time with its ground truth, and
// before it every depth frame that has arrived by then (stamped latency
// after its true capture), in order. The consumer pairs them as the daemon
// does (algo/frame_pairer.hpp). For depthkey-eval, the tests and the
// recorder of test sequences.
#pragma once

#include "hal/sim/lecture_simulator.hpp"
#include "hal/sim/sim_timing.hpp"

#include <functional>

namespace depthkey {

class SimSequence
{
public:
	using DepthHandler = std::function<void(const DepthFrame &)>;

	void configure(const SimSettings &settings, int colourWidth, int colourHeight, int colourFps, int depthFps);

	// Hands the depth frames stamped at or before colour frame n's time (and
	// not handed out before) to onDepth, then renders colour frame n and its
	// truth. Frames are meant to be asked for in increasing n.
	void frame(uint64_t n, ColourFrame &colour, GroundTruth &truth, const DepthHandler &onDepth);

	LectureSimulator &simulator() { return simulator_; }
	const sim::SimTiming &timing() const { return timing_; }

private:
	LectureSimulator simulator_;
	sim::SimTiming timing_;
	DepthFrame depth_;
	int64_t nextDepth_ = 0;
};

} // namespace depthkey
