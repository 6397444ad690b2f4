#include "daemon/snapshot_writer.hpp"

#include "algo/trimap.hpp"

#include <cerrno>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sys/stat.h>

namespace depthkey {

namespace {

constexpr int kSmallWidth = 320; // narrower images are enlarged 4x

bool writePng(const std::string &path, const cv::Mat &mat, std::string &error)
{
	bool ok = false;
	try {
		ok = cv::imwrite(path, mat);
	} catch (const cv::Exception &e) {
		error = path + ": " + e.what();
		return false;
	}
	if (!ok)
		error = path + ": cannot write";
	return ok;
}

cv::Mat enlargeIfSmall(const cv::Mat &mat)
{
	if (mat.cols >= kSmallWidth)
		return mat;
	cv::Mat big;
	cv::resize(mat, big, cv::Size(mat.cols * 4, mat.rows * 4), 0, 0, cv::INTER_NEAREST);
	return big;
}

cv::Mat drawStage(const StageImage &stage)
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

} // namespace

int writeStageImages(const std::string &dir, const std::string &prefix, const StageImages &stages,
		     std::string &error)
{
	if (mkdir(dir.c_str(), 0755) < 0 && errno != EEXIST) {
		int ret = -errno;
		error = dir + ": cannot create folder";
		return ret;
	}
	for (const StageImage &stage : stages.items()) {
		cv::Mat picture = drawStage(stage);
		if (picture.empty())
			continue;
		if (!writePng(dir + "/" + prefix + stage.name + ".png", picture, error))
			return -EIO;
	}
	return 0;
}

} // namespace depthkey
