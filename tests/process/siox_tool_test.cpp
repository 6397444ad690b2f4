// The depthkey-siox tool end to end: a synthetic still and its trimap in,
// mask and soft alpha out; bad input refused with exit status 1.
#include "hal/image_file.hpp"
#include "tests/synthetic_still.hpp"
#include "tests/test_paths.hpp"

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <cstdlib>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

using namespace depthkey;
using namespace depthkey::test;

namespace {

struct TempDir {
	std::string path;
	TempDir()
	{
		char tmpl[] = "/tmp/depthkey-siox-XXXXXX";
		path = mkdtemp(tmpl);
	}
	~TempDir() { std::system(("rm -rf " + path).c_str()); }
};

int runTool(const std::string &args)
{
	std::string cmd = binDir() + "/depthkey-siox " + args + " 2>/dev/null";
	int status = std::system(cmd.c_str());
	return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

int writeRgbPng(const std::string &path, const RgbImage &image)
{
	// A PNG through imgcodecs; tests/process/siox_formats_test.cpp has the other formats.
	cv::Mat rgb(image.height(), image.width(), CV_8UC3, const_cast<Rgb8 *>(image.data())), bgr;
	cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
	return cv::imwrite(path, bgr) ? 0 : -1;
}

} // namespace

TEST(DepthkeySiox, SegmentsASyntheticImageAndWritesMaskAndAlpha)
{
	TempDir dir;
	SyntheticStill s = makeStill(320, 240, 10, 2);
	std::string error;
	ASSERT_EQ(writeRgbPng(dir.path + "/image.png", s.image), 0);
	ASSERT_EQ(writePng(dir.path + "/trimap.png", s.trimap, error), 0) << error;
	ASSERT_EQ(runTool(dir.path + "/image.png " + dir.path + "/trimap.png " + dir.path + "/mask.png --alpha " +
			  dir.path + "/alpha.png"),
		  0);
	Gray8Image mask, alpha;
	ASSERT_EQ(readGray8Image(dir.path + "/mask.png", mask, error), 0) << error;
	ASSERT_EQ(readGray8Image(dir.path + "/alpha.png", alpha, error), 0) << error;
	EXPECT_GE(intersectionOverUnion(mask, s.truth), 0.97);
	size_t fractional = 0;
	for (size_t i = 0; i < mask.size(); ++i) {
		ASSERT_TRUE(mask.data()[i] == 0 || mask.data()[i] == 255);
		ASSERT_EQ(mask.data()[i], alpha.data()[i] >= 128 ? 255 : 0);
		fractional += alpha.data()[i] != 0 && alpha.data()[i] != 255;
	}
	EXPECT_GT(fractional, 100u); // the boundary is soft
}

TEST(DepthkeySiox, FailsClearlyOnBadInput)
{
	TempDir dir;
	SyntheticStill s = makeStill(64, 48, 6, 1);
	std::string error;
	writeRgbPng(dir.path + "/image.png", s.image);
	writePng(dir.path + "/trimap.png", s.trimap, error);
	Gray8Image small(10, 10);
	writePng(dir.path + "/small.png", small, error);
	writeRgbPng(dir.path + "/colour-trimap.ppm", s.image);
	EXPECT_EQ(runTool(""), 1);
	EXPECT_EQ(runTool(dir.path + "/missing.png " + dir.path + "/trimap.png " + dir.path + "/m.png"), 1);
	EXPECT_EQ(runTool(dir.path + "/image.png " + dir.path + "/small.png " + dir.path + "/m.png"), 1);
	EXPECT_EQ(runTool(dir.path + "/image.png " + dir.path + "/colour-trimap.ppm " + dir.path + "/m.png"), 1);
	EXPECT_EQ(runTool(dir.path + "/image.png " + dir.path + "/trimap.png " + dir.path + "/m.png --smoothing 9"), 1);
	EXPECT_EQ(runTool(dir.path + "/image.png " + dir.path + "/trimap.png /nonexistent-dir/m.png"), 1);
}
