#include "algo/pipeline_stages.hpp"

namespace depthkey {

void collectPipelineStages(const ColourFrame &colour, const DepthFrame &depth, const PipelineOutput &output,
			   StageImages &stages)
{
	if (!colour.rgb.empty())
		stages.add("colour", colour.rgb);
	if (!depth.depthMm.empty())
		stages.addDepth("depth", depth.depthMm);
	if (!output.alpha.empty()) {
		// The hard decision before matting: in the skeleton the alpha is
		// already binary, so both look alike.
		Gray8Image &segmentation = stages.ownGray("segmentation", StageKind::Mask);
		segmentation.resize(output.alpha.width(), output.alpha.height());
		for (size_t i = 0; i < output.alpha.size(); ++i)
			segmentation.data()[i] = output.alpha.data()[i] >= 128 ? 255 : 0;
		stages.add("alpha", StageKind::Mask, output.alpha);
	}
	if (!output.composite.empty())
		stages.add("composite", output.composite);
}

} // namespace depthkey
