#include "daemon/no_signal_picture.hpp"

#include "algo/no_signal_frame.hpp"

#include <algorithm>

namespace depthkey {

void NoSignalPicture::fill(const std::string &cameraName, int width, int height, PipelineOutput &output)
{
	const std::string text = "NO SIGNAL: " + cameraName;
	if (picture_.width() != width || picture_.height() != height || text != text_) {
		picture_.resize(width, height);
		renderNoSignalFrame(text, picture_);
		text_ = text;
	}
	output.composite = picture_;
	output.alpha.resize(width, height);
	std::fill(output.alpha.data(), output.alpha.data() + output.alpha.size(), 0);
}

} // namespace depthkey
