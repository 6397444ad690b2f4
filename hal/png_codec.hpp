// PNG in and out with libpng itself, not OpenCV's imgcodecs: Debian's
// imgcodecs maps GDAL, poppler, HDF5 and about 130 other libraries into every
// process that links it (issue 15), for the two formats the project reads.
// libpng is a dependency already (the header check of image_file_reader).
//
// libpng reports errors by longjmp; both functions catch them in one C++
// frame that holds no object with a destructor across the jump, and turn
// them into error values.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace depthkey {

// An image file's pixels as it stores them, rows packed: channels 1 (grey),
// 2 (grey + alpha), 3 (RGB) or 4 (RGBA), 8 or 16 bits a sample (16-bit
// samples in host order). Palettes come out as RGB, grey below 8 bits as 8.
// pixels is reused from call to call: it reallocates only to grow.
struct DecodedImage {
	int width = 0;
	int height = 0;
	int channels = 0;
	int bitDepth = 0;
	std::vector<uint8_t> pixels;
};

// Decodes a whole PNG in memory. Returns 0, or -EINVAL with why set
// (libpng's own words: "file ends early", "IDAT: CRC error", ...).
// maxWidth/maxHeight bound what libpng accepts, as a second guard behind
// the header check of the caller.
int decodePng(const uint8_t *data, size_t size, int maxWidth, int maxHeight, DecodedImage &out,
	      std::string &why);

// Pixels to write: rows of `stride` bytes, channels 1 or 3 (3 in RGB order,
// or BGR when bgr), 8 or 16 bits a sample (16 in host order).
struct PngPixels {
	const void *data = nullptr;
	int width = 0;
	int height = 0;
	size_t stride = 0;
	int channels = 0;
	int bitDepth = 8;
	bool bgr = false;
};

// What OpenCV's imwrite did, so that recordings and snapshots keep their
// size and speed: zlib level 1 with the "sub" filter by default; with a
// level 0..9 given, that level and libpng's per-row choice of filters. The
// zlib strategy is Z_RLE either way (OpenCV's default).
constexpr int kPngFastCompression = -1;

// Writes path (created or truncated). Returns 0, or a negative errno with
// error "PATH: why"; a file left half-written is removed.
int encodePng(const std::string &path, const PngPixels &pixels, int compression, std::string &error);

} // namespace depthkey
