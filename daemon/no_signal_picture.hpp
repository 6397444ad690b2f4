// What goes out while the colour camera delivers nothing: a NO SIGNAL
// picture naming the camera (algo/no_signal_frame.hpp) as the composite and
// nothing keyed, so that consumers never starve. The picture is rendered
// again only when its text or size changes, not once per frame, and let go
// of when frames come again (a colour frame's worth of memory, 0.9 MB at
// 640x480, that the daemon would otherwise keep for the next outage).
#pragma once

#include "algo/image.hpp"
#include "algo/pipeline.hpp"

#include <string>

namespace depthkey {

class NoSignalPicture
{
public:
	// Fills output as a keyed frame would: the picture as the composite, a
	// transparent lecturer layer and alpha, at width x height.
	void fill(const std::string &cameraName, int width, int height, PipelineOutput &output);
	// Frames are keyed again: the picture is not needed until the next outage.
	void forget()
	{
		if (!picture_.empty()) {
			picture_ = RgbImage();
			text_.clear();
		}
	}

private:
	RgbImage picture_;
	std::string text_;
};

} // namespace depthkey
