#include "tools/siox/still_image_reader.hpp"

#include "hal/image_file.hpp"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace depthkey {

#ifndef DEPTHKEY_NO_IMGCODECS
namespace {

constexpr const char *kFormats = "PNG, JPEG, BMP, TIFF, PNM or WebP";

// imread answers every failure with an empty Mat, so the reasons a person
// can act on (missing, unreadable, a folder, not an image) are found first.
int checkReadable(const std::string &path, std::string &error)
{
	int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
	if (fd < 0) {
		int err = errno;
		error = path + ": " + std::strerror(err);
		return -err;
	}
	struct stat st {};
	int ret = ::fstat(fd, &st);
	::close(fd);
	if (ret < 0 || !S_ISREG(st.st_mode)) {
		error = path + ": not a regular file";
		return -EINVAL;
	}
	if (st.st_size == 0) {
		error = path + ": empty file";
		return -EINVAL;
	}
	return 0;
}

int decode(const std::string &path, int flags, cv::Mat &out, std::string &error)
{
	if (int ret = checkReadable(path, error); ret < 0)
		return ret;
	try {
		if (!cv::haveImageReader(path)) {
			error = path + ": not a " + std::string(kFormats) + " file (its signature is none of them)";
			return -EINVAL;
		}
		out = cv::imread(path, flags);
	} catch (const cv::Exception &e) {
		// Some decoders throw on corrupt data rather than return nothing.
		error = path + ": corrupt image data (" + e.err + ")";
		return -EINVAL;
	}
	if (out.empty()) {
		error = path + ": corrupt or truncated image data (its header names a known format, "
			       "but it does not decode)";
		return -EINVAL;
	}
	return 0;
}

} // namespace
#endif

int readStillRgb(const std::string &path, RgbImage &out, std::string &error)
{
#ifdef DEPTHKEY_NO_IMGCODECS
	// The arm64 build has no imgcodecs (arch/arm64/imgcodecs_unavailable.cpp):
	// PNG and JPEG through the project's own reader.
	return readRgbImage(path, out, error);
#else
	cv::Mat bgr;
	if (int ret = decode(path, cv::IMREAD_COLOR, bgr, error); ret < 0)
		return ret;
	out = RgbImage(bgr.cols, bgr.rows);
	cv::Mat rgb(bgr.rows, bgr.cols, CV_8UC3, out.data());
	cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
	return 0;
#endif
}

int readStillTrimap(const std::string &path, Gray8Image &out, std::string &error)
{
#ifdef DEPTHKEY_NO_IMGCODECS
	return readGray8Image(path, out, error);
#else
	cv::Mat file;
	if (int ret = decode(path, cv::IMREAD_UNCHANGED, file, error); ret < 0)
		return ret;
	if (file.depth() != CV_8U) {
		error = path + ": a trimap must have 8-bit samples, this file has " +
			std::to_string(file.elemSize1() * 8) + "-bit ones";
		return -EINVAL;
	}
	out = Gray8Image(file.cols, file.rows);
	for (int y = 0; y < file.rows; ++y) {
		const uint8_t *row = file.ptr<uint8_t>(y);
		for (int x = 0; x < file.cols; ++x) {
			const uint8_t *px = row + size_t(x) * file.channels();
			if (file.channels() >= 3 && (px[0] != px[1] || px[1] != px[2])) {
				error = path + ": a trimap must be grey, but pixel (" + std::to_string(x) + ", " +
					std::to_string(y) + ") is coloured";
				return -EINVAL;
			}
			out.data()[size_t(y) * file.cols + x] = px[0];
		}
	}
	return 0;
#endif
}

} // namespace depthkey
