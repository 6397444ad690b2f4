#include "algo/pipeline.hpp"

#include "algo/composite.hpp"

namespace depthkey {

void Pipeline::configure(const SegmentationSettings &segmentation, const CompositeSettings &composite)
{
	segmentation_ = segmentation;
	if (!(composite == compositeSettings_))
		boardDirty_ = true;
	compositeSettings_ = composite;
	opacityQ8_ = opacityToQ8(composite.opacity);
}

void Pipeline::ensureSizes(int colourWidth, int colourHeight, int depthWidth, int depthHeight)
{
	if (colourWidth != colourWidth_ || colourHeight != colourHeight_ ||
	    depthWidth != depthWidth_ || depthHeight != depthHeight_) {
		colourWidth_ = colourWidth;
		colourHeight_ = colourHeight;
		depthWidth_ = depthWidth;
		depthHeight_ = depthHeight;
		keyer_.configure(colourWidth, colourHeight, depthWidth, depthHeight);
		boardDirty_ = true;
	}
	if (boardDirty_) {
		uint32_t c = compositeSettings_.boardColour;
		Rgb8 colour{ static_cast<uint8_t>(c >> 16), static_cast<uint8_t>(c >> 8),
			     static_cast<uint8_t>(c) };
		board_ = RgbImage(colourWidth, colourHeight, colour);
		boardDirty_ = false;
	}
}

void Pipeline::process(const ColourFrame &colour, const DepthFrame &depth, PipelineOutput &out)
{
	ensureSizes(colour.rgb.width(), colour.rgb.height(), depth.depthMm.width(),
		    depth.depthMm.height());
	keyer_.key(depth.depthMm, segmentation_.nearMm, segmentation_.farMm, out.alpha);
	composite(colour.rgb, out.alpha, board_, opacityQ8_, out.composite);
	lecturerLayer(colour.rgb, out.alpha, out.lecturer);
}

void Pipeline::passThrough(const ColourFrame &colour, PipelineOutput &out)
{
	out.alpha.resize(colour.rgb.width(), colour.rgb.height());
	for (size_t i = 0; i < out.alpha.size(); ++i)
		out.alpha.data()[i] = 255;
	out.composite.resize(colour.rgb.width(), colour.rgb.height());
	std::copy(colour.rgb.data(), colour.rgb.data() + colour.rgb.size(), out.composite.data());
	lecturerLayer(colour.rgb, out.alpha, out.lecturer);
}

} // namespace depthkey
