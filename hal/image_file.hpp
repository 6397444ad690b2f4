// Image files in and out (OpenCV imgcodecs: PNG, JPEG, ...) as algo/ images,
// with errors as values naming the file and what is wrong with it. Every PNG
// the daemon and the tools write goes through here, so that the image
// library's exceptions (a full disk, an unwritable folder) come back as
// -EIO with the file named, never as a throw through the event loop.
#pragma once

#include "algo/image.hpp"

#include <string>

namespace cv {
class Mat;
}

namespace depthkey {

// Any 8-bit colour or grey file, as RGB. -ENOENT / -EINVAL with error set.
int readRgbImage(const std::string &path, RgbImage &out, std::string &error);
// An 8-bit single-channel file (a trimap): colour files are refused, since
// converting them would silently turn labels into other labels.
int readGray8Image(const std::string &path, Gray8Image &out, std::string &error);

// OpenCV's own PNG settings (zlib level 1 with the "sub" filter), unless a
// zlib level 0..9 is given (the recorder's, which then lets libpng choose
// its filters per row).
constexpr int kDefaultPngCompression = -1;

// PNG files of algo/ images: RGB as RGB, grey as grey (8 or 16 bits).
// Return 0 or -EIO with error "PATH: why".
int writePng(const std::string &path, const RgbImage &image, std::string &error,
	     int pngCompression = kDefaultPngCompression);
int writePng(const std::string &path, const Gray8Image &image, std::string &error,
	     int pngCompression = kDefaultPngCompression);
int writePng(const std::string &path, const Gray16Image &image, std::string &error,
	     int pngCompression = kDefaultPngCompression);
// A picture drawn with OpenCV for people to look at (BGR or grey, as
// imwrite takes it). Return 0 or -EIO with error "PATH: why".
int writePicturePng(const std::string &path, const cv::Mat &picture, std::string &error,
		    int pngCompression = kDefaultPngCompression);

} // namespace depthkey
