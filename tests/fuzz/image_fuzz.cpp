// libFuzzer harness: PNG and JPEG files through the project's own reader
// (header checked against the limits, then libpng or TurboJPEG decodes).
// The limits are smaller than the daemon's so that each run stays fast, the
// code path is the same. The first byte is skipped, as it chose OpenCV's
// decode flags before, so that the stored corpus keeps its meaning.
#include "hal/image_file_reader.hpp"

#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	using namespace depthkey;
	if (size < 1)
		return 0;
	const ImageLimits limits{ 256, 256 };
	std::string bytes(reinterpret_cast<const char *>(data) + 1, size - 1);
	DecodedImage image;
	std::string error;
	int ret = decodeImageBytes(bytes, "fuzz.png", limits, image, error);
	const size_t expected = size_t(image.width) * size_t(image.height) * size_t(image.channels) *
				size_t(image.bitDepth / 8);
	if (ret == 0 && (image.width < 1 || image.height < 1 || image.width > limits.maxWidth ||
			 image.height > limits.maxHeight || image.pixels.size() != expected))
		std::abort();
	if (ret < 0 && (error.empty() || image.width != 0))
		std::abort();
	return 0;
}
