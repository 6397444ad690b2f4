// libFuzzer harness: PNG and JPEG files through the project's own reader
// (header checked against the limits, then OpenCV decodes). The first byte
// chooses how it is decoded; the limits are smaller than the daemon's so
// that each run stays fast, the code path is the same.
#include "hal/image_file_reader.hpp"

#include <cstdlib>
#include <opencv2/imgcodecs.hpp>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	using namespace depthkey;
	if (size < 1)
		return 0;
	constexpr int kFlags[] = { cv::IMREAD_COLOR, cv::IMREAD_UNCHANGED, cv::IMREAD_GRAYSCALE };
	const ImageLimits limits{ 256, 256 };
	std::string bytes(reinterpret_cast<const char *>(data) + 1, size - 1);
	cv::Mat image;
	std::string error;
	int ret = decodeImageBytes(bytes, "fuzz.png", limits, kFlags[data[0] % 3], image, error);
	if (ret == 0 && (image.empty() || image.cols > limits.maxWidth || image.rows > limits.maxHeight))
		std::abort();
	if (ret < 0 && (error.empty() || !image.empty()))
		std::abort();
	return 0;
}
