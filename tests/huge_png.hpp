// A PNG that is small on disk but claims a huge size: the input of case G
// of issue 14 (one 20000x20000 PNG of 5 MB in a replay sequence).
#pragma once

#include <cstdio>
#include <png.h>
#include <string>
#include <vector>

namespace depthkey::test {

// 1-bit grey, all black: a 20000x20000 image deflates to about 60 kB.
inline bool writeHugePng(const std::string &path, unsigned width, unsigned height)
{
	std::FILE *f = std::fopen(path.c_str(), "wb");
	if (!f)
		return false;
	png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
	png_infop info = png ? png_create_info_struct(png) : nullptr;
	bool ok = png && info && setjmp(png_jmpbuf(png)) == 0;
	if (ok) {
		png_init_io(png, f);
		png_set_IHDR(png, info, width, height, 1, PNG_COLOR_TYPE_GRAY, PNG_INTERLACE_NONE,
			     PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
		png_write_info(png, info);
		std::vector<png_byte> row((width + 7) / 8, 0);
		for (unsigned y = 0; y < height; y++)
			png_write_row(png, row.data());
		png_write_end(png, nullptr);
	}
	png_destroy_write_struct(&png, &info);
	std::fclose(f);
	return ok;
}

} // namespace depthkey::test
