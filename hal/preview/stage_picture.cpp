#include "hal/preview/stage_picture.hpp"

#include "algo/trimap.hpp"

#include <opencv2/imgproc.hpp>

namespace depthkey {

namespace {

constexpr int kSmallWidth = 320; // narrower images are enlarged 4x

cv::Mat enlargeIfSmall(const cv::Mat &mat)
{
	if (mat.cols >= kSmallWidth)
		return mat;
	cv::Mat big;
	cv::resize(mat, big, cv::Size(mat.cols * 4, mat.rows * 4), 0, 0, cv::INTER_NEAREST);
	return big;
}

} // namespace

cv::Mat drawStagePicture(const StageImage &stage)
{
	cv::Mat out;
	if (stage.rgb && !stage.rgb->empty()) {
		cv::Mat rgb(stage.rgb->height(), stage.rgb->width(), CV_8UC3, const_cast<Rgb8 *>(stage.rgb->data()));
		cv::cvtColor(rgb, out, cv::COLOR_RGB2BGR);
	} else if (stage.depth && !stage.depth->empty()) {
		cv::Mat depth(stage.depth->height(), stage.depth->width(), CV_16UC1,
			      const_cast<uint16_t *>(stage.depth->data()));
		// 0.5 m .. 4.0 m spread over the colour map; nearer is warmer.
		cv::Mat scaled;
		depth.convertTo(scaled, CV_8UC1, -255.0 / 3500.0, 255.0 * 4000.0 / 3500.0);
		cv::applyColorMap(scaled, out, cv::COLORMAP_JET);
		out.setTo(cv::Scalar(0, 0, 0), depth == 0);
	} else if (stage.gray && !stage.gray->empty()) {
		cv::Mat gray(stage.gray->height(), stage.gray->width(), CV_8UC1,
			     const_cast<uint8_t *>(stage.gray->data()));
		if (stage.kind == StageKind::Seeds) {
			out.create(gray.rows, gray.cols, CV_8UC3);
			out.setTo(cv::Scalar(128, 128, 128));                     // undecided: grey
			out.setTo(cv::Scalar(200, 80, 40), gray == kTrimapBoard);    // board: blue (BGR)
			out.setTo(cv::Scalar(0, 140, 255), gray == kTrimapLecturer); // lecturer: orange
		} else {
			out = gray;
		}
	}
	return out.empty() ? out : enlargeIfSmall(out);
}

} // namespace depthkey
