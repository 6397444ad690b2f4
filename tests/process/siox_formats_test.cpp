// depthkey-siox reads what image editors read (issue 30): a still and its
// trimap in each of PNG, JPEG, BMP, TIFF, PNM and WebP, written here with
// OpenCV's imgcodecs, segment as the PNG does; a file of each format whose
// signature is right but whose data is garbage is refused with the file
// named and the reason, exit status 1.
#include "hal/image_file.hpp"
#include "tests/process/shell_command.hpp"
#include "tests/synthetic_still.hpp"
#include "tests/test_paths.hpp"

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

using namespace depthkey;
using namespace depthkey::test;

namespace {

struct Format {
	const char *imageExt;
	const char *trimapExt;	     // lossy formats would turn 0/255 labels into "undecided"
	std::vector<int> params;     // imwrite's, e.g. lossless WebP
	size_t signatureBytes;	     // what haveImageReader recognises the format by
};

const Format kFormats[] = {
	{".png", ".png", {}, 8},
	{".jpg", ".png", {cv::IMWRITE_JPEG_QUALITY, 95}, 3},
	{".bmp", ".bmp", {}, 2},
	{".tiff", ".tiff", {}, 4},
	{".ppm", ".pgm", {}, 3}, // "P6" and its whitespace
	{".webp", ".webp", {cv::IMWRITE_WEBP_QUALITY, 101}, 30}, // >100: lossless
};

struct TempDir {
	std::string path;
	TempDir()
	{
		char tmpl[] = "/tmp/depthkey-siox-formats-XXXXXX";
		path = mkdtemp(tmpl);
	}
	~TempDir() { std::system(("rm -rf " + path).c_str()); }
};

bool writeImage(const std::string &path, const RgbImage &image, const std::vector<int> &params)
{
	cv::Mat rgb(image.height(), image.width(), CV_8UC3, const_cast<Rgb8 *>(image.data())), bgr;
	cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
	return cv::imwrite(path, bgr, params);
}

bool writeTrimap(const std::string &path, const Gray8Image &trimap, const std::vector<int> &params)
{
	cv::Mat grey(trimap.height(), trimap.width(), CV_8UC1, const_cast<uint8_t *>(trimap.data()));
	return cv::imwrite(path, grey, path.ends_with(".webp") ? params : std::vector<int>{});
}

std::string siox(const std::string &args, int &status)
{
	return run(binDir() + "/depthkey-siox " + args, status);
}

// The file's first bytes (its format's signature), then bytes that are no
// image data of any format.
void corrupt(const std::string &from, const std::string &to, size_t keep)
{
	std::ifstream in(from, std::ios::binary);
	std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
	ASSERT_GT(bytes.size(), keep);
	bytes.resize(keep);
	bytes.append(200, '\xa5');
	std::ofstream(to, std::ios::binary) << bytes;
}

} // namespace

TEST(DepthkeySioxFormats, EachFormatSegmentsLikeThePng)
{
#ifdef DEPTHKEY_NO_IMGCODECS
	GTEST_SKIP() << "the arm64 build has no imgcodecs (Makefile, ARCH=arm64)";
#endif
	TempDir dir;
	SyntheticStill s = makeStill(160, 120, 8, 3);
	for (const Format &f : kFormats) {
		SCOPED_TRACE(f.imageExt);
		std::string image = dir.path + "/image" + f.imageExt, trimap = dir.path + "/trimap" + f.imageExt;
		trimap = trimap.substr(0, trimap.rfind('.')) + f.trimapExt;
		ASSERT_TRUE(writeImage(image, s.image, f.params));
		ASSERT_TRUE(writeTrimap(trimap, s.trimap, f.params));
		std::string mask = dir.path + "/mask" + f.imageExt + ".png";
		int status = 0;
		std::string out = siox(image + " " + trimap + " " + mask, status);
		ASSERT_EQ(status, 0) << out;
		Gray8Image result;
		std::string error;
		ASSERT_EQ(readGray8Image(mask, result, error), 0) << error;
		EXPECT_GE(intersectionOverUnion(result, s.truth), 0.95);
	}
}

TEST(DepthkeySioxFormats, ACorruptFileOfEachFormatIsNamedWithTheReason)
{
#ifdef DEPTHKEY_NO_IMGCODECS
	GTEST_SKIP() << "the arm64 build has no imgcodecs (Makefile, ARCH=arm64)";
#endif
	TempDir dir;
	SyntheticStill s = makeStill(64, 48, 6, 1);
	std::string goodTrimap = dir.path + "/trimap.png", error;
	ASSERT_EQ(writePng(goodTrimap, s.trimap, error), 0) << error;
	for (const Format &f : kFormats) {
		SCOPED_TRACE(f.imageExt);
		std::string good = dir.path + "/good" + f.imageExt, bad = dir.path + "/bad" + f.imageExt;
		ASSERT_TRUE(writeImage(good, s.image, f.params));
		corrupt(good, bad, f.signatureBytes);
		int status = 0;
		std::string out = siox(bad + " " + goodTrimap + " " + dir.path + "/m.png", status);
		EXPECT_EQ(status, 1);
		EXPECT_NE(out.find("depthkey-siox: " + bad + ": corrupt"), std::string::npos) << out;
		// The same as a trimap.
		out = siox(good + " " + bad + " " + dir.path + "/m.png", status);
		EXPECT_EQ(status, 1);
		EXPECT_NE(out.find("depthkey-siox: " + bad + ": corrupt"), std::string::npos) << out;
	}
}

TEST(DepthkeySioxFormats, UnknownEmptyAndColouredFilesAreRefusedByName)
{
#ifdef DEPTHKEY_NO_IMGCODECS
	GTEST_SKIP() << "the arm64 build has no imgcodecs (Makefile, ARCH=arm64)";
#endif
	TempDir dir;
	SyntheticStill s = makeStill(64, 48, 6, 1);
	std::string image = dir.path + "/image.bmp", text = dir.path + "/notes.txt", empty = dir.path + "/empty.tiff";
	std::string colourTrimap = dir.path + "/trimap.webp";
	ASSERT_TRUE(writeImage(image, s.image, {}));
	ASSERT_TRUE(writeImage(colourTrimap, s.image, {cv::IMWRITE_WEBP_QUALITY, 101}));
	std::ofstream(text) << "not a picture\n";
	std::ofstream{empty};
	int status = 0;
	std::string out = siox(text + " " + image + " " + dir.path + "/m.png", status);
	EXPECT_EQ(status, 1);
	EXPECT_NE(out.find(text + ": not a PNG, JPEG, BMP, TIFF, PNM or WebP file"), std::string::npos) << out;
	out = siox(empty + " " + image + " " + dir.path + "/m.png", status);
	EXPECT_EQ(status, 1);
	EXPECT_NE(out.find(empty + ": empty file"), std::string::npos) << out;
	out = siox(image + " " + colourTrimap + " " + dir.path + "/m.png", status);
	EXPECT_EQ(status, 1);
	EXPECT_NE(out.find(colourTrimap + ": a trimap must be grey, but pixel ("), std::string::npos) << out;
}
