// The per-frame segmentation: a colour frame and the depth frame paired with
// it in, the alpha matte, composite and lecturer layer out. Pure: no I/O, no
// clock; buffers are allocated when the sizes change, never per frame.
#pragma once

#include "algo/depth_range_keyer.hpp"
#include "algo/frames.hpp"
#include "config/settings.hpp"

namespace depthkey {

struct PipelineOutput {
	Gray8Image alpha;     // 255 = lecturer
	RgbImage composite;   // lecturer over the board source
	RgbaImage lecturer;   // straight alpha
};

class Pipeline
{
public:
	// Takes the parameters that may change on reload; cheap when unchanged.
	void configure(const SegmentationSettings &segmentation, const CompositeSettings &composite);

	void process(const ColourFrame &colour, const DepthFrame &depth, PipelineOutput &out);

	// What is published when the depth camera is missing: the colour frame as
	// it is (lecturer layer opaque), since a plain picture beats a black one.
	void passThrough(const ColourFrame &colour, PipelineOutput &out);

private:
	void ensureSizes(int colourWidth, int colourHeight, int depthWidth, int depthHeight);

	SegmentationSettings segmentation_;
	CompositeSettings compositeSettings_;
	int opacityQ8_ = 128;
	DepthRangeKeyer keyer_;
	RgbImage board_;
	int colourWidth_ = 0, colourHeight_ = 0, depthWidth_ = 0, depthHeight_ = 0;
	bool boardDirty_ = true;
};

} // namespace depthkey
