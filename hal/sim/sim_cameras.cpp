#include "hal/sim/sim_cameras.hpp"

namespace depthkey {

void SimColourCamera::prepare()
{
	simulator_.configure(sim_, settings_.width, settings_.height);
	timing_.configure(sim_, settings_.fps, 10); // the depth rate does not matter here
}

uint64_t SimColourCamera::captureDelayUs(uint64_t n) const
{
	return static_cast<uint64_t>(timing_.colourCaptureDelay(n) * 1e6);
}

void SimColourCamera::render(uint64_t nowUs, ColourFrame &frame)
{
	if (technician_)
		simulator_.setCalibrationTarget(technician_->targetAt(nowUs / 1e6));
	simulator_.renderColour(nowUs / 1e6, frame, &truth_);
	// The daemon's live score (issue 29) reads it where the frame is published.
	frame.truth = truth_.alpha;
}

void SimDepthCamera::prepare()
{
	// The colour size does not matter for the depth view.
	simulator_.configure(sim_, 640, 480);
	timing_.configure(sim_, 25, settings_.fps);
}

void SimDepthCamera::render(uint64_t nowUs, DepthFrame &frame)
{
	// The frame shows the scene latency (and jitter) before it arrives.
	double shown = nowUs / 1e6 - sim_.depthLatencyMs / 1000.0 -
		       sim_.depthJitterMs / 1000.0 * timing_.jitterUnit(2, frame.sequence);
	if (technician_)
		simulator_.setCalibrationTarget(technician_->targetAt(shown));
	simulator_.renderDepth(shown, frame);
}

} // namespace depthkey
