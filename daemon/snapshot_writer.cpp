#include "daemon/snapshot_writer.hpp"

#include <cerrno>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sys/stat.h>

namespace depthkey {

namespace {

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

} // namespace

int writeSnapshotImages(const std::string &dir, const SnapshotImages &images, std::string &error)
{
	if (mkdir(dir.c_str(), 0755) < 0 && errno != EEXIST) {
		int ret = -errno;
		error = dir + ": cannot create folder";
		return ret;
	}
	auto rgbToBgr = [](const RgbImage &image) {
		cv::Mat rgb(image.height(), image.width(), CV_8UC3, const_cast<Rgb8 *>(image.data()));
		cv::Mat bgr;
		cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
		return bgr;
	};
	if (!images.colour.empty() && !writePng(dir + "/colour.png", rgbToBgr(images.colour), error))
		return -EIO;
	if (!images.composite.empty() &&
	    !writePng(dir + "/composite.png", rgbToBgr(images.composite), error))
		return -EIO;
	if (!images.alpha.empty()) {
		cv::Mat alpha(images.alpha.height(), images.alpha.width(), CV_8UC1,
			      const_cast<uint8_t *>(images.alpha.data()));
		if (!writePng(dir + "/alpha.png", alpha, error))
			return -EIO;
	}
	if (!images.depthMm.empty()) {
		cv::Mat depth(images.depthMm.height(), images.depthMm.width(), CV_16UC1,
			      const_cast<uint16_t *>(images.depthMm.data()));
		// 0.5 m .. 4.0 m spread over the colour map; nearer is warmer.
		cv::Mat scaled, coloured;
		depth.convertTo(scaled, CV_8UC1, -255.0 / 3500.0, 255.0 * 4000.0 / 3500.0);
		cv::applyColorMap(scaled, coloured, cv::COLORMAP_JET);
		if (!writePng(dir + "/depth.png", coloured, error))
			return -EIO;
	}
	return 0;
}

} // namespace depthkey
