// Lists the pipeline's stage images for one processed frame pair, in the
// order data flows: colour, depth, depth mapped into colour, seeds,
// segmentation, alpha matte, composite. Stages the pipeline does not have
// yet (the skeleton maps no depth and makes no seeds) are left out; the
// pipeline adds them here as it grows.
#pragma once

#include "algo/frames.hpp"
#include "algo/pipeline.hpp"
#include "algo/stage_images.hpp"

namespace depthkey {

void collectPipelineStages(const ColourFrame &colour, const DepthFrame &depth, const PipelineOutput &output,
			   StageImages &stages);

} // namespace depthkey
