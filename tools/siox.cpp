// depthkey-siox: SIOX on one still image, as GIMP's foreground select does it.
//
//   depthkey-siox IMAGE TRIMAP OUT_MASK [--alpha OUT_ALPHA] [--smoothing N] [--hard]
//
// IMAGE and TRIMAP may be PNG, JPEG, BMP, TIFF, PNM or WebP
// (tools/siox/still_image_reader.hpp). TRIMAP is 8-bit grey of IMAGE's size: 0 = background (board), 255 =
// foreground (lecturer), any other value = undecided. OUT_MASK is an 8-bit
// PNG, 0 / 255; OUT_ALPHA the soft matte 0..255. Exit 0, or 1 with a message.
#include "algo/still_siox.hpp"
#include "hal/image_file.hpp"
#include "tools/siox/still_image_reader.hpp"

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

using namespace depthkey;

namespace {

int usage()
{
	std::fprintf(stderr, "usage: depthkey-siox IMAGE TRIMAP OUT_MASK [--alpha OUT_ALPHA] "
			     "[--smoothing 0..8] [--hard]\n"
			     "IMAGE and TRIMAP: PNG, JPEG, BMP, TIFF, PNM (PBM/PGM/PPM) or WebP\n");
	return 1;
}

int fail(const std::string &message)
{
	std::fprintf(stderr, "depthkey-siox: %s\n", message.c_str());
	return 1;
}

} // namespace

int main(int argc, char **argv)
{
	std::string positional[3], alphaPath;
	int count = 0;
	SioxSettings settings;
	for (int i = 1; i < argc; ++i) {
		std::string arg = argv[i];
		if (arg == "--alpha" && i + 1 < argc) {
			alphaPath = argv[++i];
		} else if (arg == "--smoothing" && i + 1 < argc) {
			char *end = nullptr;
			long n = std::strtol(argv[++i], &end, 10);
			if (*end || n < 0 || n > 8)
				return fail(std::string("--smoothing must be 0..8, not \"") + argv[i] + "\"");
			settings.smoothing = int(n);
		} else if (arg == "--hard") {
			settings.softAlpha = false;
		} else if (arg == "-h" || arg == "--help") {
			usage();
			return 0;
		} else if (!arg.empty() && arg[0] == '-') {
			return usage();
		} else if (count < 3) {
			positional[count++] = arg;
		} else {
			return usage();
		}
	}
	if (count != 3)
		return usage();

	RgbImage image;
	Gray8Image trimap, mask, alpha;
	std::string error;
	if (readStillRgb(positional[0], image, error) < 0 || readStillTrimap(positional[1], trimap, error) < 0)
		return fail(error);
	if (trimap.width() != image.width() || trimap.height() != image.height())
		return fail(positional[1] + ": trimap is " + std::to_string(trimap.width()) + "x" +
			    std::to_string(trimap.height()) + ", image is " + std::to_string(image.width()) +
			    "x" + std::to_string(image.height()));

	StillSiox siox;
	siox.configure(settings);
	int ret = siox.segment(image, trimap, mask, alpha);
	if (ret == -ENODATA)
		return fail(positional[1] + ": no background (0) pixel: SIOX needs known board colours");
	if (ret < 0)
		return fail(std::string("segmentation failed: ") + std::strerror(-ret));
	if (writePng(positional[2], mask, error) < 0 ||
	    (!alphaPath.empty() && writePng(alphaPath, alpha, error) < 0))
		return fail(error);
	return 0;
}
