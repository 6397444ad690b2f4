#include "hal/sim/sim_timing.hpp"

#include "hal/sim/hash_noise.hpp"

#include <algorithm>
#include <cmath>

namespace depthkey::sim {

void SimTiming::configure(const SimSettings &settings, int colourFps, int depthFps)
{
	seed_ = settings.seed;
	colourPeriod_ = 1.0 / colourFps;
	depthPeriod_ = 1.0 / depthFps;
	// Jitter below half a period keeps the frames in order.
	colourJitter_ = std::min(settings.colourJitterMs / 1000.0, 0.45 * colourPeriod_);
	depthJitter_ = std::min(settings.depthJitterMs / 1000.0, 0.45 * depthPeriod_);
	latency_ = settings.depthLatencyMs / 1000.0;
}

double SimTiming::jitterUnit(uint64_t stream, uint64_t n) const
{
	return uniformFromHash(hashKey(seed_, stream, n)) * 2.0 - 1.0;
}

double SimTiming::colourTime(uint64_t n) const
{
	// Frame 0 is never early, so that no time is negative.
	return colourJitter_ + n * colourPeriod_ + colourJitter_ * jitterUnit(1, n);
}

double SimTiming::colourCaptureDelay(uint64_t n) const
{
	return colourJitter_ - colourJitter_ * jitterUnit(1, n);
}

double SimTiming::depthCapture(uint64_t m) const
{
	// The ToF starts a third of its period after the colour camera.
	return depthJitter_ + (m + 0.33) * depthPeriod_ + depthJitter_ * jitterUnit(2, m);
}

double SimTiming::depthStamp(uint64_t m) const
{
	return depthCapture(m) + latency_;
}

int64_t SimTiming::latestDepthAt(double timeS) const
{
	int64_t guess = static_cast<int64_t>(std::floor((timeS - latency_) / depthPeriod_)) + 2;
	for (int64_t m = std::max<int64_t>(guess, 0); m >= 0; --m)
		if (depthStamp(static_cast<uint64_t>(m)) <= timeS)
			return m;
	return -1;
}

} // namespace depthkey::sim
