// Image files in and out (OpenCV imgcodecs: PNG, JPEG, ...) as algo/ images,
// with errors as values naming the file and what is wrong with it.
#pragma once

#include "algo/image.hpp"

#include <string>

namespace depthkey {

// Any 8-bit colour or grey file, as RGB. -ENOENT / -EINVAL with error set.
int readRgbImage(const std::string &path, RgbImage &out, std::string &error);
// An 8-bit single-channel file (a trimap): colour files are refused, since
// converting them would silently turn labels into other labels.
int readGray8Image(const std::string &path, Gray8Image &out, std::string &error);
// PNG of an 8-bit grey image. -EIO with error set.
int writeGray8Png(const std::string &path, const Gray8Image &image, std::string &error);

} // namespace depthkey
