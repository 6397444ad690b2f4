// depthkey-siox's image files: what image editors open (PNG, JPEG, BMP,
// TIFF, PNM and WebP), read through OpenCV's imgcodecs. Only this tool links
// imgcodecs (Debian's maps GDAL, poppler and ~130 more libraries: issue 15);
// the daemon keeps its own PNG/JPEG reader (hal/image_file_reader.hpp).
#pragma once

#include "algo/image.hpp"

#include <string>

namespace depthkey {

// The image as 8-bit RGB (grey is widened, alpha dropped, 16-bit scaled
// down). Returns 0, or a negative errno with error "PATH: why": -ENOENT /
// -EACCES when it cannot be opened, -EINVAL when it is no image of those
// formats or its data is corrupt.
int readStillRgb(const std::string &path, RgbImage &out, std::string &error);

// An 8-bit trimap: grey, or colour whose every pixel is grey (a WebP has no
// grey form). Other colour files and 16-bit files are refused, since
// converting them would silently turn labels into other labels.
int readStillTrimap(const std::string &path, Gray8Image &out, std::string &error);

} // namespace depthkey
