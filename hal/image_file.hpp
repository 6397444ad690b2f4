// Image files in and out (PNG through libpng, JPEG through TurboJPEG:
// hal/png_codec.hpp) as algo/ images, with errors as values naming the file
// and what is wrong with it. Every PNG the daemon and the tools write goes
// through here, so that a full disk or an unwritable folder comes back as a
// negative errno with the file named, never as a throw through the event loop.
#pragma once

#include "algo/image.hpp"
#include "hal/png_codec.hpp"

#include <string>

namespace cv {
class Mat;
}

namespace depthkey {

// Any 8-bit colour or grey PNG or JPEG, as RGB (an alpha channel is
// dropped). -ENOENT / -EINVAL / -EFBIG with error set.
int readRgbImage(const std::string &path, RgbImage &out, std::string &error);
// An 8-bit single-channel file (a trimap): colour files are refused, since
// converting them would silently turn labels into other labels.
int readGray8Image(const std::string &path, Gray8Image &out, std::string &error);

// zlib level 1 with the "sub" filter (OpenCV's imwrite settings, which
// recordings were made with), unless a zlib level 0..9 is given (the
// recorder's, which then lets libpng choose its filters per row).
constexpr int kDefaultPngCompression = kPngFastCompression;

// PNG files of algo/ images: RGB as RGB, grey as grey (8 or 16 bits).
// Return 0 or a negative errno with error "PATH: why" (-EIO when writing
// failed part way; the partial file is removed, -EINVAL for an empty image).
int writePng(const std::string &path, const RgbImage &image, std::string &error,
	     int pngCompression = kDefaultPngCompression);
int writePng(const std::string &path, const Gray8Image &image, std::string &error,
	     int pngCompression = kDefaultPngCompression);
int writePng(const std::string &path, const Gray16Image &image, std::string &error,
	     int pngCompression = kDefaultPngCompression);
// A picture drawn with OpenCV for people to look at (8-bit BGR or grey, as
// imwrite took it; depthkey-calibrate's views). The same returns. Only
// cv::Mat's inline members: it adds no OpenCV library to a link.
int writePicturePng(const std::string &path, const cv::Mat &picture, std::string &error,
		    int pngCompression = kDefaultPngCompression);

} // namespace depthkey
