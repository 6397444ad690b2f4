#include "hal/image_file.hpp"

#include <cerrno>
#include <cstring>

#include "config/frame_limits.hpp"
#include "hal/image_file_reader.hpp"

#include <opencv2/core/mat.hpp>

namespace depthkey {

namespace {

// Board images and stills: bounded like every file read (image_file_reader).
// The decoded pixels are freed again at once: a daemon that read a large
// board image at a reload keeps no copy of it.
int readDecoded(const std::string &path, DecodedImage &image, std::string &error)
{
	int ret = decodeImageFile(path, { kMaxBoardImageSide, kMaxBoardImageSide }, image, error);
	if (ret < 0)
		return ret;
	if (image.bitDepth != 8) {
		error = path + ": must have 8 bits per channel";
		return -EINVAL;
	}
	return 0;
}

} // namespace

int readRgbImage(const std::string &path, RgbImage &out, std::string &error)
{
	DecodedImage image;
	int ret = readDecoded(path, image, error);
	if (ret < 0)
		return ret;
	out.resize(image.width, image.height);
	const uint8_t *in = image.pixels.data();
	const int step = image.channels;
	Rgb8 *px = out.data();
	// Grey (1), grey + alpha (2), RGB (3) or RGBA (4): colour from the first
	// channel or the first three, alpha dropped.
	for (size_t i = 0; i < out.size(); ++i, in += step)
		px[i] = step < 3 ? Rgb8{ in[0], in[0], in[0] } : Rgb8{ in[0], in[1], in[2] };
	return 0;
}

int readGray8Image(const std::string &path, Gray8Image &out, std::string &error)
{
	DecodedImage image;
	int ret = readDecoded(path, image, error);
	if (ret < 0)
		return ret;
	if (image.channels != 1) {
		error = path + ": must be a single-channel (grey) 8-bit image, has " +
			std::to_string(image.channels) + " channels";
		return -EINVAL;
	}
	out.resize(image.width, image.height);
	std::memcpy(out.data(), image.pixels.data(), out.size());
	return 0;
}

int writePicturePng(const std::string &path, const cv::Mat &picture, std::string &error, int pngCompression)
{
	if (picture.depth() != CV_8U || (picture.channels() != 1 && picture.channels() != 3)) {
		error = path + ": cannot write a picture of type " + std::to_string(picture.type());
		return -EINVAL;
	}
	PngPixels pixels{ picture.data, picture.cols, picture.rows, picture.step[0], picture.channels(), 8, true };
	return encodePng(path, pixels, pngCompression, error);
}

int writePng(const std::string &path, const RgbImage &image, std::string &error, int pngCompression)
{
	PngPixels pixels{ image.data(), image.width(), image.height(), size_t(image.width()) * 3, 3, 8, false };
	return encodePng(path, pixels, pngCompression, error);
}

int writePng(const std::string &path, const Gray8Image &image, std::string &error, int pngCompression)
{
	PngPixels pixels{ image.data(), image.width(), image.height(), size_t(image.width()), 1, 8, false };
	return encodePng(path, pixels, pngCompression, error);
}

int writePng(const std::string &path, const Gray16Image &image, std::string &error, int pngCompression)
{
	PngPixels pixels{ image.data(), image.width(), image.height(), size_t(image.width()) * 2, 1, 16, false };
	return encodePng(path, pixels, pngCompression, error);
}

} // namespace depthkey
