#include "hal/png_codec.hpp"

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <png.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

namespace depthkey {

namespace {

constexpr bool kLittleEndian = std::endian::native == std::endian::little;

// Everything libpng's callbacks need; plain data, so that a longjmp out of
// libpng skips no destructor.
struct PngContext {
	const uint8_t *data = nullptr;
	size_t size = 0;
	size_t pos = 0;
	char message[160] = "";
};

[[noreturn]] void onError(png_structp png, png_const_charp message)
{
	auto *ctx = static_cast<PngContext *>(png_get_error_ptr(png));
	std::snprintf(ctx->message, sizeof(ctx->message), "%s", message);
	png_longjmp(png, 1);
}

// Warnings (an sRGB profile libpng knows to be off, a text chunk too long)
// never change the pixels; libpng would print them on stderr.
void onWarning(png_structp, png_const_charp)
{
}

void readFromMemory(png_structp png, png_bytep out, size_t n)
{
	auto *ctx = static_cast<PngContext *>(png_get_io_ptr(png));
	if (n > ctx->size - ctx->pos)
		png_error(png, "file ends early");
	std::memcpy(out, ctx->data + ctx->pos, n);
	ctx->pos += n;
}

} // namespace

int decodePng(const uint8_t *data, size_t size, int maxWidth, int maxHeight, DecodedImage &out,
	      std::string &why)
{
	PngContext ctx;
	ctx.data = data;
	ctx.size = size;
	png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &ctx, onError, onWarning);
	png_infop info = png ? png_create_info_struct(png) : nullptr;
	if (!info) {
		png_destroy_read_struct(&png, nullptr, nullptr);
		why = "out of memory";
		return -ENOMEM;
	}
	if (setjmp(png_jmpbuf(png))) {
		png_destroy_read_struct(&png, &info, nullptr);
		why = ctx.message;
		return -EINVAL;
	}
	png_set_user_limits(png, png_uint_32(std::max(maxWidth, 1)), png_uint_32(std::max(maxHeight, 1)));
	png_set_read_fn(png, &ctx, readFromMemory);
	png_read_info(png, info);
	const int colourType = png_get_color_type(png, info);
	const int fileDepth = png_get_bit_depth(png, info);
	if (colourType == PNG_COLOR_TYPE_PALETTE)
		png_set_palette_to_rgb(png);
	if (colourType == PNG_COLOR_TYPE_GRAY && fileDepth < 8)
		png_set_expand_gray_1_2_4_to_8(png);
	if (fileDepth == 16 && kLittleEndian)
		png_set_swap(png);
	const int passes = png_set_interlace_handling(png);
	png_read_update_info(png, info);
	out.width = static_cast<int>(png_get_image_width(png, info));
	out.height = static_cast<int>(png_get_image_height(png, info));
	out.channels = png_get_channels(png, info);
	out.bitDepth = png_get_bit_depth(png, info);
	const size_t rowBytes = png_get_rowbytes(png, info);
	out.pixels.resize(rowBytes * size_t(out.height));
	// Row by row, each interlace pass over the same rows: no row pointer
	// array to allocate.
	for (int pass = 0; pass < passes; ++pass)
		for (int y = 0; y < out.height; ++y)
			png_read_row(png, out.pixels.data() + rowBytes * size_t(y), nullptr);
	png_read_end(png, nullptr);
	png_destroy_read_struct(&png, &info, nullptr);
	return 0;
}

namespace {

// The part of encodePng between setjmp and the end of libpng's work: file
// and structs are its caller's, so a longjmp leaves nothing to destroy here.
bool writeRows(png_structp png, png_infop info, std::FILE *file, const PngPixels &p, int compression)
{
	if (setjmp(png_jmpbuf(png)))
		return false;
	png_init_io(png, file);
	png_set_IHDR(png, info, png_uint_32(p.width), png_uint_32(p.height), p.bitDepth,
		     p.channels == 1 ? PNG_COLOR_TYPE_GRAY : PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
		     PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
	if (compression == kPngFastCompression) {
		png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB);
		png_set_compression_level(png, Z_BEST_SPEED);
	} else {
		png_set_compression_level(png, std::clamp(compression, 0, 9));
	}
	png_set_compression_strategy(png, Z_RLE);
	png_write_info(png, info);
	if (p.bgr)
		png_set_bgr(png);
	if (p.bitDepth == 16 && kLittleEndian)
		png_set_swap(png);
	const auto *bytes = static_cast<const uint8_t *>(p.data);
	for (int y = 0; y < p.height; ++y)
		png_write_row(png, const_cast<png_bytep>(bytes + p.stride * size_t(y)));
	png_write_end(png, info);
	return true;
}

} // namespace

int encodePng(const std::string &path, const PngPixels &p, int compression, std::string &error)
{
	if (!p.data || p.width < 1 || p.height < 1 || (p.channels != 1 && p.channels != 3) ||
	    (p.bitDepth != 8 && p.bitDepth != 16)) {
		error = path + ": cannot write an empty image or one of " + std::to_string(p.channels) +
			" channels, " + std::to_string(p.bitDepth) + " bits";
		return -EINVAL;
	}
	std::FILE *file = std::fopen(path.c_str(), "wbe");
	if (!file) {
		int err = errno;
		error = path + ": cannot write: " + std::strerror(err);
		return -err;
	}
	// Only a regular file that was half written is removed again: never
	// a device or FIFO that path named.
	struct stat st;
	const bool regular = fstat(fileno(file), &st) == 0 && S_ISREG(st.st_mode);
	PngContext ctx;
	png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &ctx, onError, onWarning);
	png_infop info = png ? png_create_info_struct(png) : nullptr;
	bool ok = info && writeRows(png, info, file, p, compression);
	png_destroy_write_struct(&png, &info);
	// fclose flushes the last block: a full disk can show only here.
	ok = std::fclose(file) == 0 && ok;
	if (!ok) {
		int err = errno;
		error = path + ": cannot write: " + (ctx.message[0] ? ctx.message : std::strerror(err));
		if (regular)
			unlink(path.c_str());
		return -EIO;
	}
	return 0;
}

} // namespace depthkey
