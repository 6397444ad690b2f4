#include "hal/sim/sim_sequence.hpp"

#include <cmath>

namespace depthkey {

void SimSequence::configure(const SimSettings &settings, int colourWidth, int colourHeight, int colourFps,
			    int depthFps)
{
	simulator_.configure(settings, colourWidth, colourHeight);
	timing_.configure(settings, colourFps, depthFps);
	nextDepth_ = 0;
}

void SimSequence::frame(uint64_t n, ColourFrame &colour, GroundTruth &truth, const DepthHandler &onDepth)
{
	double t = timing_.colourTime(n);
	for (int64_t last = timing_.latestDepthAt(t); nextDepth_ <= last; ++nextDepth_) {
		uint64_t m = static_cast<uint64_t>(nextDepth_);
		simulator_.renderDepth(timing_.depthCapture(m), depth_);
		depth_.timestampNs = static_cast<uint64_t>(std::llround(timing_.depthStamp(m) * 1e9));
		depth_.sequence = m + 1;
		onDepth(depth_);
	}
	simulator_.renderColour(t, colour, &truth);
	colour.sequence = n + 1;
}

} // namespace depthkey
