// The sections of the settings the pipeline reads, and only those: what can
// reconfigure it is then plain from its signature, and a reload that changes
// any other section (devices, output, LEDs) cannot touch it.
#pragma once

#include "settings/settings.hpp"

#include <cstdint>

namespace depthkey {

struct PipelineSettings {
	SegmentationSettings segmentation;
	LearningSettings learning;
	SioxSettings siox;
	DecisionSettings decision;
	CompositeSettings composite;
	// board.colour: the camera-geometry composite's board while no picture is set.
	uint32_t boardColour = BoardSettings{}.colour;
	bool operator==(const PipelineSettings &) const = default;

	static PipelineSettings from(const Settings &settings)
	{
		return { settings.segmentation, settings.learning, settings.siox, settings.decision, settings.composite,
			 settings.board.colour };
	}
};

} // namespace depthkey
