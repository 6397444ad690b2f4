#include "algo/no_signal_frame.hpp"

#include <opencv2/imgproc.hpp>

namespace depthkey {

void renderNoSignalFrame(const std::string &text, RgbImage &out)
{
	const int w = out.width(), h = out.height();
	if (w <= 0 || h <= 0)
		return;
	cv::Mat mat(h, w, CV_8UC3, out.data());
	// Seven dim colour bars, the look every technician recognises.
	static const cv::Scalar bars[] = { { 96, 96, 96 }, { 96, 96, 0 }, { 0, 96, 96 }, { 0, 96, 0 },
					   { 96, 0, 96 }, { 96, 0, 0 }, { 0, 0, 96 } };
	for (int i = 0; i < 7; ++i)
		cv::rectangle(mat, cv::Point(i * w / 7, 0), cv::Point((i + 1) * w / 7, h), bars[i],
			      cv::FILLED);
	double scale = w / 640.0;
	int baseline = 0;
	cv::Size size = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, scale, 2, &baseline);
	cv::Point origin((w - size.width) / 2, (h + size.height) / 2);
	cv::rectangle(mat, origin + cv::Point(-8, baseline + 8),
		      origin + cv::Point(size.width + 8, -size.height - 8), cv::Scalar(0, 0, 0), cv::FILLED);
	cv::putText(mat, text, origin, cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar(255, 255, 255), 2,
		    cv::LINE_AA);
}

} // namespace depthkey
