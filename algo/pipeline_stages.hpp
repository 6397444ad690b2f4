// Lists the pipeline's stage images for one processed frame pair, in the
// order data flows: colour, depth, depth mapped into colour, the depth seeds
// (at ToF resolution and mapped into colour: surely lecturer, surely board,
// undecided band), segmentation, alpha matte, composite. The pipeline's own
// images are borrowed; the mapped depth and the segmentation are made here,
// for the preview only.
#pragma once

#include "algo/frames.hpp"
#include "algo/mapping_model.hpp"
#include "algo/pipeline.hpp"
#include "algo/stage_images.hpp"

namespace depthkey {

void collectPipelineStages(const ColourFrame &colour, const DepthFrame &depth, const Pipeline &pipeline,
			   const PipelineOutput &output, const MappingModel &mapping, StageImages &stages);

// Depth drawn into the colour image through the mapping (each ToF pixel
// splatted over the colour pixels it covers, the nearer depth winning; 0 =
// no measurement). For previews and the depth-only baseline; out is resized
// to the colour size.
void mapDepthToColour(const Gray16Image &depthMm, const MappingModel &mapping, int colourWidth, int colourHeight,
		      Gray16Image &out);

} // namespace depthkey
