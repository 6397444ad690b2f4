#include "hal/image_file.hpp"

#include <cerrno>
#include <cstring>
#include <vector>

#include "config/frame_limits.hpp"
#include "hal/image_file_reader.hpp"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace depthkey {

namespace {

// Board images and stills: bounded like every file read (image_file_reader).
int readMat(const std::string &path, int flags, cv::Mat &mat, std::string &error)
{
	int ret = decodeImageFile(path, { kMaxBoardImageSide, kMaxBoardImageSide }, flags, mat, error);
	if (ret < 0)
		return ret;
	if (mat.depth() != CV_8U) {
		error = path + ": must have 8 bits per channel";
		return -EINVAL;
	}
	return 0;
}

} // namespace

int readRgbImage(const std::string &path, RgbImage &out, std::string &error)
{
	cv::Mat mat;
	int ret = readMat(path, cv::IMREAD_COLOR | cv::IMREAD_ANYDEPTH, mat, error);
	if (ret < 0)
		return ret;
	out.resize(mat.cols, mat.rows);
	cv::Mat rgb(mat.rows, mat.cols, CV_8UC3, out.data());
	cv::cvtColor(mat, rgb, cv::COLOR_BGR2RGB);
	return 0;
}

int readGray8Image(const std::string &path, Gray8Image &out, std::string &error)
{
	cv::Mat mat;
	int ret = readMat(path, cv::IMREAD_UNCHANGED, mat, error);
	if (ret < 0)
		return ret;
	if (mat.channels() != 1) {
		error = path + ": must be a single-channel (grey) 8-bit image, has " +
			std::to_string(mat.channels()) + " channels";
		return -EINVAL;
	}
	out.resize(mat.cols, mat.rows);
	for (int y = 0; y < mat.rows; ++y)
		std::memcpy(out.row(y), mat.ptr<uint8_t>(y), size_t(mat.cols));
	return 0;
}

int writePicturePng(const std::string &path, const cv::Mat &picture, std::string &error, int pngCompression)
{
	std::vector<int> params;
	if (pngCompression != kDefaultPngCompression)
		params = { cv::IMWRITE_PNG_COMPRESSION, pngCompression };
	bool ok = false;
	try {
		ok = cv::imwrite(path, picture, params);
	} catch (const cv::Exception &e) {
		error = path + ": " + e.what();
		return -EIO;
	}
	if (!ok) {
		error = path + ": cannot write";
		return -EIO;
	}
	return 0;
}

int writePng(const std::string &path, const RgbImage &image, std::string &error, int pngCompression)
{
	cv::Mat rgb(image.height(), image.width(), CV_8UC3, const_cast<Rgb8 *>(image.data()));
	cv::Mat bgr;
	try {
		cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR); // imwrite takes BGR
	} catch (const cv::Exception &e) { // an empty image
		error = path + ": " + e.what();
		return -EIO;
	}
	return writePicturePng(path, bgr, error, pngCompression);
}

int writePng(const std::string &path, const Gray8Image &image, std::string &error, int pngCompression)
{
	cv::Mat mat(image.height(), image.width(), CV_8UC1, const_cast<uint8_t *>(image.data()));
	return writePicturePng(path, mat, error, pngCompression);
}

int writePng(const std::string &path, const Gray16Image &image, std::string &error, int pngCompression)
{
	cv::Mat mat(image.height(), image.width(), CV_16UC1, const_cast<uint16_t *>(image.data()));
	return writePicturePng(path, mat, error, pngCompression);
}

} // namespace depthkey
