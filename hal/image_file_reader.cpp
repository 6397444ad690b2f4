#include "hal/image_file_reader.hpp"

#include "config/text_file.hpp"
#include "config/frame_limits.hpp"

#include <cerrno>
#include <cstring>

#include <opencv2/imgcodecs.hpp>
#include <png.h>
#include <turbojpeg.h>

namespace depthkey {

namespace {

bool pngSize(const unsigned char *data, size_t size, int &width, int &height)
{
	if (size < 8 || png_sig_cmp(data, 0, 8) != 0)
		return false;
	png_image image;
	std::memset(&image, 0, sizeof(image));
	image.version = PNG_IMAGE_VERSION;
	// Reads the signature and IHDR only; no pixel memory is allocated.
	bool ok = png_image_begin_read_from_memory(&image, data, size) != 0;
	if (ok) {
		width = static_cast<int>(std::min<png_uint_32>(image.width, 1u << 30));
		height = static_cast<int>(std::min<png_uint_32>(image.height, 1u << 30));
	}
	png_image_free(&image);
	return ok;
}

bool jpegSize(const unsigned char *data, size_t size, int &width, int &height)
{
	if (size < 3 || data[0] != 0xff || data[1] != 0xd8)
		return false;
	tjhandle handle = tjInitDecompress();
	if (!handle)
		return false;
	int subsampling = 0, colourspace = 0;
	bool ok = tjDecompressHeader3(handle, data, static_cast<unsigned long>(size), &width, &height,
				      &subsampling, &colourspace) == 0;
	tjDestroy(handle);
	return ok;
}

} // namespace

bool imageHeaderSize(const unsigned char *data, size_t size, int &width, int &height)
{
	return pngSize(data, size, width, height) || jpegSize(data, size, width, height);
}

int decodeImageFile(const std::string &path, const ImageLimits &limits, int cvFlags, cv::Mat &out,
		    std::string &error)
{
	out.release();
	std::string bytes, why;
	int ret = readTextFile(path, kMaxImageFileBytes, bytes, why);
	if (ret < 0) {
		error = path + ": cannot read: " + why;
		return ret;
	}
	return decodeImageBytes(bytes, path, limits, cvFlags, out, error);
}

int decodeImageBytes(const std::string &bytes, const std::string &path, const ImageLimits &limits,
		     int cvFlags, cv::Mat &out, std::string &error)
{
	out.release();
	const auto *data = reinterpret_cast<const unsigned char *>(bytes.data());
	int width = 0, height = 0;
	if (!imageHeaderSize(data, bytes.size(), width, height)) {
		error = path + ": not a PNG or JPEG file (or its header is corrupt)";
		return -EINVAL;
	}
	if (width < 1 || height < 1 || width > limits.maxWidth || height > limits.maxHeight) {
		error = path + ": " + std::to_string(width) + "x" + std::to_string(height) +
			" pixels, larger than the " + std::to_string(limits.maxWidth) + "x" +
			std::to_string(limits.maxHeight) + " accepted";
		return -EFBIG;
	}
	try {
		cv::Mat raw(1, static_cast<int>(bytes.size()), CV_8UC1, const_cast<char *>(bytes.data()));
		out = cv::imdecode(raw, cvFlags);
	} catch (const cv::Exception &e) {
		out.release();
	}
	if (out.empty()) {
		error = path + ": corrupt image data";
		return -EINVAL;
	}
	// The header was checked, but a decoder could still disagree with it.
	if (out.cols > limits.maxWidth || out.rows > limits.maxHeight) {
		out.release();
		error = path + ": decoded larger than its header says";
		return -EINVAL;
	}
	return 0;
}

} // namespace depthkey
