// Decoding an image file that anybody may have put there: read like a config
// (regular file, O_NONBLOCK, size cap: config/text_file.hpp), its PNG or JPEG
// header's dimensions checked against limits, and only then decoded, with
// libpng (hal/png_codec.hpp) or TurboJPEG.
#pragma once

#include "hal/png_codec.hpp"

#include <string>

namespace depthkey {

struct ImageLimits {
	int maxWidth = 0;
	int maxHeight = 0;
};

// PNG or JPEG only: those are the formats whose headers are checked. out
// gets the pixels as the file stores them (DecodedImage: a JPEG as 8-bit
// grey or RGB). Returns 0, or a negative errno with error naming path and
// what is wrong: -EFBIG for dimensions over limits, -EINVAL for not an
// image or corrupt data.
int decodeImageFile(const std::string &path, const ImageLimits &limits, DecodedImage &out, std::string &error);

// The same for a file's bytes already in memory; name is what errors say.
int decodeImageBytes(const std::string &bytes, const std::string &name, const ImageLimits &limits,
		     DecodedImage &out, std::string &error);

// The header's dimensions of a PNG or JPEG in memory; false when it is
// neither (or the header is corrupt). For decodeImageFile and the fuzzers.
bool imageHeaderSize(const unsigned char *data, size_t size, int &width, int &height);

} // namespace depthkey
