#include "algo/pipeline_stages.hpp"

#include <algorithm>
#include <cmath>

namespace depthkey {

void mapDepthToColour(const Gray16Image &depthMm, const MappingModel &mapping, int colourWidth, int colourHeight,
		      Gray16Image &out)
{
	out.resize(colourWidth, colourHeight);
	std::fill(out.data(), out.data() + out.size(), uint16_t{ 0 });
	MappingModel model = mapping;
	// The model is fitted for its sizes; scale to the frames at hand.
	const double sx = double(colourWidth) / model.colourWidth, sy = double(colourHeight) / model.colourHeight;
	const double su = double(model.tofWidth) / std::max(1, depthMm.width());
	const double sv = double(model.tofHeight) / std::max(1, depthMm.height());
	// Half the spacing of neighbouring ToF pixels in the colour image (the
	// widest, over the image at 1.5 m), rounded up: splats leave no holes.
	double spanX = 0, spanY = 0;
	for (int v = 0; v + 1 < depthMm.height(); v += std::max(1, depthMm.height() / 4))
		for (int u = 0; u + 1 < depthMm.width(); u += std::max(1, depthMm.width() / 4)) {
			double x0, y0, x1, y1, x2, y2;
			model.map((u + 0.5) * su - 0.5, (v + 0.5) * sv - 0.5, 1.5, x0, y0);
			model.map((u + 1.5) * su - 0.5, (v + 0.5) * sv - 0.5, 1.5, x1, y1);
			model.map((u + 0.5) * su - 0.5, (v + 1.5) * sv - 0.5, 1.5, x2, y2);
			spanX = std::max(spanX, std::hypot(x1 - x0, y1 - y0) * sx);
			spanY = std::max(spanY, std::hypot(x2 - x0, y2 - y0) * sy);
		}
	const int rx = static_cast<int>(std::ceil(spanX / 2)), ry = static_cast<int>(std::ceil(spanY / 2));
	for (int v = 0; v < depthMm.height(); ++v)
		for (int u = 0; u < depthMm.width(); ++u) {
			uint16_t z = depthMm.at(u, v);
			if (!z)
				continue;
			double x, y;
			model.map((u + 0.5) * su - 0.5, (v + 0.5) * sv - 0.5, z / 1000.0, x, y);
			int cx = static_cast<int>(std::lround(x * sx)), cy = static_cast<int>(std::lround(y * sy));
			for (int yy = std::max(0, cy - ry); yy <= std::min(colourHeight - 1, cy + ry); ++yy) {
				uint16_t *row = out.row(yy);
				for (int xx = std::max(0, cx - rx); xx <= std::min(colourWidth - 1, cx + rx); ++xx)
					if (!row[xx] || z < row[xx])
						row[xx] = z;
			}
		}
}

void collectPipelineStages(const ColourFrame &colour, const DepthFrame &depth, const Pipeline &pipeline,
			   const PipelineOutput &output, const MappingModel &mapping, StageImages &stages)
{
	if (!colour.rgb.empty())
		stages.add("colour", colour.rgb);
	if (!depth.depthMm.empty()) {
		stages.addDepth("depth", depth.depthMm);
		if (!colour.rgb.empty()) {
			Gray16Image &mapped = stages.ownDepth("depth-mapped");
			mapDepthToColour(depth.depthMm, mapping, colour.rgb.width(), colour.rgb.height(), mapped);
		}
	}
	if (!pipeline.seeds().labels.empty())
		stages.add("seeds-tof", StageKind::Seeds, pipeline.seeds().labels);
	if (!pipeline.trimap().empty())
		stages.add("seeds", StageKind::Seeds, pipeline.trimap());
	if (!pipeline.depthEvidence().empty())
		stages.add("depth-evidence", StageKind::Mask, pipeline.depthEvidence());
	if (!colour.rgb.empty()) {
		Gray8Image &confidence = stages.ownGray("siox-confidence", StageKind::Mask);
		pipeline.confidence(colour.rgb, confidence);
	}
	if (!output.alpha.empty()) {
		// The hard decision, before the soft matte.
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
