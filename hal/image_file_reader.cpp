#include "hal/image_file_reader.hpp"

#include "config/text_file.hpp"
#include "config/frame_limits.hpp"

#include <cerrno>
#include <cstring>

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

// Grey JPEGs stay grey, the rest become RGB. TurboJPEG's defaults are
// libjpeg's (accurate integer IDCT, fancy upsampling), as OpenCV decoded.
// A warning (a truncated or damaged file, decoded in part) is an error: a
// half-grey picture is never taken for the real one.
int decodeJpeg(const unsigned char *data, size_t size, DecodedImage &out, std::string &why)
{
	tjhandle handle = tjInitDecompress();
	if (!handle) {
		why = "out of memory";
		return -ENOMEM;
	}
	int width = 0, height = 0, subsampling = 0, colourspace = 0;
	int ret = 0;
	if (tjDecompressHeader3(handle, data, static_cast<unsigned long>(size), &width, &height, &subsampling,
				&colourspace) != 0) {
		why = tjGetErrorStr2(handle);
		ret = -EINVAL;
	} else if (colourspace == TJCS_CMYK || colourspace == TJCS_YCCK) {
		why = "a CMYK JPEG, not grey or colour";
		ret = -EINVAL;
	} else {
		out.width = width;
		out.height = height;
		out.channels = colourspace == TJCS_GRAY ? 1 : 3;
		out.bitDepth = 8;
		out.pixels.resize(size_t(width) * size_t(height) * size_t(out.channels));
		if (tjDecompress2(handle, data, static_cast<unsigned long>(size), out.pixels.data(), width, 0, height,
				  out.channels == 1 ? TJPF_GRAY : TJPF_RGB, 0) != 0) {
			why = tjGetErrorStr2(handle);
			ret = -EINVAL;
		}
	}
	tjDestroy(handle);
	return ret;
}

} // namespace

bool imageHeaderSize(const unsigned char *data, size_t size, int &width, int &height)
{
	return pngSize(data, size, width, height) || jpegSize(data, size, width, height);
}

int decodeImageFile(const std::string &path, const ImageLimits &limits, DecodedImage &out, std::string &error)
{
	out.width = out.height = out.channels = out.bitDepth = 0;
	std::string bytes, why;
	int ret = readTextFile(path, kMaxImageFileBytes, bytes, why);
	if (ret < 0) {
		error = path + ": cannot read: " + why;
		return ret;
	}
	return decodeImageBytes(bytes, path, limits, out, error);
}

int decodeImageBytes(const std::string &bytes, const std::string &path, const ImageLimits &limits,
		     DecodedImage &out, std::string &error)
{
	out.width = out.height = out.channels = out.bitDepth = 0;
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
	std::string why;
	int ret = data[0] == 0xff ? decodeJpeg(data, bytes.size(), out, why)
				  : decodePng(data, bytes.size(), limits.maxWidth, limits.maxHeight, out, why);
	if (ret < 0) {
		out.width = out.height = out.channels = out.bitDepth = 0;
		error = path + ": corrupt image data (" + why + ")";
		return ret == -ENOMEM ? ret : -EINVAL;
	}
	// The header was checked, but a decoder could still disagree with it.
	if (out.width != width || out.height != height) {
		out.width = out.height = out.channels = out.bitDepth = 0;
		error = path + ": decoded to another size than its header says";
		return -EINVAL;
	}
	return 0;
}

} // namespace depthkey
