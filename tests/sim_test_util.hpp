// Helpers for the simulator tests: settings with every artefact off, and
// small statistics over images.
#pragma once

#include "settings/settings.hpp"

namespace depthkey::test {

// The simulated scene with no artefact at all: a clean reference that a
// test switches single artefacts back on in.
inline SimSettings cleanSim()
{
	SimSettings s;
	s.lightingChange = false;
	s.colourNoise = 0;
	s.colourJitterMs = 0;
	s.depthNoise = false;
	s.haloWidthPx = 0;
	s.saturationMm = 0;
	s.motionBlur = false;
	s.depthLatencyMs = 0;
	s.depthJitterMs = 0;
	return s;
}

} // namespace depthkey::test
