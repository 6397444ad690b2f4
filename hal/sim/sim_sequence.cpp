#include "hal/sim/sim_sequence.hpp"

#include <cmath>

namespace depthkey {

void SimSequence::configure(const SimSettings &settings, int colourWidth, int colourHeight, int colourFps,
			    int depthFps)
{
	simulator_.configure(settings, colourWidth, colourHeight);
	timing_.configure(settings, colourFps, depthFps);
	depthIndex_ = -1;
}

bool SimSequence::frame(uint64_t n, ColourFrame &colour, GroundTruth &truth, DepthFrame &depth)
{
	double t = timing_.colourTime(n);
	simulator_.renderColour(t, colour, &truth);
	colour.sequence = n + 1;
	int64_t m = timing_.latestDepthAt(t);
	if (m < 0)
		return false;
	if (m != depthIndex_) {
		depthCaptureS_ = timing_.depthCapture(static_cast<uint64_t>(m));
		simulator_.renderDepth(depthCaptureS_, depth_);
		depth_.timestampNs = static_cast<uint64_t>(std::llround(timing_.depthStamp(static_cast<uint64_t>(m)) * 1e9));
		depth_.sequence = static_cast<uint64_t>(m) + 1;
		depthIndex_ = m;
	}
	depth = depth_;
	return true;
}

} // namespace depthkey
