// The skeleton's minimal scene, kept only for tests/pipeline_test.cpp (the
// daemon and the tools use hal/sim/lecture_simulator.hpp): a board with a few strokes and
// a figure (head and torso) walking to and fro in front of it. Both cameras
// render the same scene at their own resolution and time, so the pipeline has
// consistent colour and depth to work on. Deterministic in time and seed.
#pragma once

#include "algo/frames.hpp"

#include <cstdint>

namespace depthkey {

class SimpleScene
{
public:
	explicit SimpleScene(uint64_t seed) : seed_(seed) {}

	static constexpr int kBoardDepthMm = 2000;
	static constexpr int kFigureDepthMm = 1200;

	void renderColour(double timeS, RgbImage &out) const;
	void renderDepth(double timeS, DepthFrame &out) const;

	// True if normalised image position (u, v in [0,1)) shows the figure.
	bool figureAt(double timeS, double u, double v) const;

private:
	uint64_t seed_;
};

} // namespace depthkey
