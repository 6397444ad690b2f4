// The project's own PNG and JPEG path (hal/png_codec.hpp, hal/image_file*.hpp:
// libpng and TurboJPEG, no imgcodecs): round trips of every pixel type it
// writes, agreement with OpenCV's imgcodecs (linked into the tests only, as
// an independent codec), and bad, short and oversized files refused with
// errors that name the file and the fault.
#include "hal/image_file.hpp"
#include "hal/image_file_reader.hpp"
#include "hal/png_codec.hpp"
#include "tests/hostile_files.hpp"
#include "tests/huge_png.hpp"

#include "tests/image_codecs.hpp"

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include <cerrno>
#include <fstream>
#include <sstream>

using namespace depthkey;
using depthkey::test::ScratchDir;

namespace {

// Odd sizes, so that no row length is a multiple of 4 or 8.
constexpr int kW = 37, kH = 23;

RgbImage pattern()
{
	RgbImage image(kW, kH);
	for (int y = 0; y < kH; ++y)
		for (int x = 0; x < kW; ++x)
			image.at(x, y) = { uint8_t(x * 7), uint8_t(y * 11), uint8_t((x * y) & 255) };
	return image;
}

std::string slurp(const std::string &path)
{
	std::ifstream in(path, std::ios::binary);
	std::stringstream s;
	s << in.rdbuf();
	return s.str();
}

void spit(const std::string &path, const std::string &bytes)
{
	std::ofstream(path, std::ios::binary) << bytes;
}

std::string encoded(const std::string &ext, const cv::Mat &mat, std::vector<int> params = {})
{
	std::vector<uchar> bytes;
	EXPECT_TRUE(cv::imencode(ext, mat, bytes, params));
	return std::string(bytes.begin(), bytes.end());
}

} // namespace

TEST(ImageCodec, RgbGreyAndDepthRoundTripExactly)
{
	ScratchDir dir;
	std::string error;
	RgbImage rgb = pattern(), rgbBack;
	ASSERT_EQ(writePng(dir / "rgb.png", rgb, error), 0) << error;
	ASSERT_EQ(readRgbImage(dir / "rgb.png", rgbBack, error), 0) << error;
	EXPECT_EQ(rgbBack, rgb);

	Gray8Image grey(kW, kH), greyBack;
	for (size_t i = 0; i < grey.size(); ++i)
		grey.data()[i] = uint8_t(i * 13);
	ASSERT_EQ(writePng(dir / "grey.png", grey, error, 9), 0) << error; // the recorder's levels too
	ASSERT_EQ(readGray8Image(dir / "grey.png", greyBack, error), 0) << error;
	EXPECT_EQ(greyBack, grey);

	Gray16Image depth(kW, kH);
	for (size_t i = 0; i < depth.size(); ++i)
		depth.data()[i] = uint16_t(i * 977 + 1); // both bytes vary: a byte-order slip shows
	ASSERT_EQ(writePng(dir / "depth.png", depth, error, 0), 0) << error;
	DecodedImage decoded;
	ASSERT_EQ(decodeImageFile(dir / "depth.png", { kW, kH }, decoded, error), 0) << error;
	ASSERT_EQ(decoded.channels, 1);
	ASSERT_EQ(decoded.bitDepth, 16);
	ASSERT_EQ(decoded.pixels.size(), depth.size() * 2);
	EXPECT_EQ(std::memcmp(decoded.pixels.data(), depth.data(), decoded.pixels.size()), 0);
}

TEST(ImageCodec, AgreesWithOpenCvBothWays)
{
	SKIP_WITHOUT_IMAGE_CODECS(); // OpenCV is the reference here
	ScratchDir dir;
	std::string error;
	RgbImage rgb = pattern();
	// Ours -> OpenCV: RGB order and 16-bit byte order as imdecode sees them.
	ASSERT_EQ(writePng(dir / "ours.png", rgb, error), 0) << error;
	cv::Mat theirs = cv::imread(dir / "ours.png", cv::IMREAD_UNCHANGED);
	ASSERT_EQ(theirs.type(), CV_8UC3);
	EXPECT_EQ(theirs.at<cv::Vec3b>(5, 9), cv::Vec3b(rgb.at(9, 5).b, rgb.at(9, 5).g, rgb.at(9, 5).r));
	Gray16Image depth(kW, kH, 0x1234);
	ASSERT_EQ(writePng(dir / "depth.png", depth, error), 0) << error;
	EXPECT_EQ(cv::imread(dir / "depth.png", cv::IMREAD_UNCHANGED).at<uint16_t>(3, 4), 0x1234);

	// OpenCV -> ours: a PNG with alpha and a JPEG, pixel for pixel.
	cv::Mat bgra(kH, kW, CV_8UC4);
	for (int y = 0; y < kH; ++y)
		for (int x = 0; x < kW; ++x)
			bgra.at<cv::Vec4b>(y, x) = cv::Vec4b(uint8_t(x), uint8_t(y), uint8_t(x + y), uint8_t(3 * x));
	spit(dir / "alpha.png", encoded(".png", bgra));
	RgbImage fromAlpha;
	ASSERT_EQ(readRgbImage(dir / "alpha.png", fromAlpha, error), 0) << error;
	EXPECT_EQ(fromAlpha.at(10, 4), (Rgb8{ 14, 4, 10 })); // alpha dropped, not blended

	cv::Mat bgr(kH, kW, CV_8UC3);
	for (int y = 0; y < kH; ++y)
		for (int x = 0; x < kW; ++x)
			bgr.at<cv::Vec3b>(y, x) = cv::Vec3b(uint8_t(x * 5), uint8_t(y * 9), uint8_t(200 - x));
	std::string jpeg = encoded(".jpg", bgr, { cv::IMWRITE_JPEG_QUALITY, 90 });
	spit(dir / "photo.jpg", jpeg);
	cv::Mat reference = cv::imdecode(std::vector<uchar>(jpeg.begin(), jpeg.end()), cv::IMREAD_COLOR);
	RgbImage photo;
	ASSERT_EQ(readRgbImage(dir / "photo.jpg", photo, error), 0) << error;
	ASSERT_EQ(photo.width(), kW);
	int worst = 0;
	for (int y = 0; y < kH; ++y)
		for (int x = 0; x < kW; ++x) {
			cv::Vec3b r = reference.at<cv::Vec3b>(y, x);
			Rgb8 p = photo.at(x, y);
			worst = std::max({ worst, std::abs(p.r - r[2]), std::abs(p.g - r[1]), std::abs(p.b - r[0]) });
		}
	EXPECT_EQ(worst, 0); // the same libjpeg-turbo IDCT and upsampling

	// A grey JPEG stays grey: a trimap may be one.
	cv::Mat greyMat(kH, kW, CV_8UC1, cv::Scalar(255));
	spit(dir / "grey.jpg", encoded(".jpg", greyMat));
	Gray8Image greyBack;
	ASSERT_EQ(readGray8Image(dir / "grey.jpg", greyBack, error), 0) << error;
	EXPECT_EQ(greyBack.at(3, 3), 255);
}

TEST(ImageCodec, PicturesFromOpenCvAreWrittenBgrToRgb)
{
	SKIP_WITHOUT_IMAGE_CODECS(); // OpenCV is the reference here
	ScratchDir dir;
	std::string error;
	cv::Mat bgr(4, 5, CV_8UC3, cv::Scalar(10, 20, 30)); // B, G, R
	ASSERT_EQ(writePicturePng(dir / "picture.png", bgr, error), 0) << error;
	RgbImage back;
	ASSERT_EQ(readRgbImage(dir / "picture.png", back, error), 0) << error;
	EXPECT_EQ(back.at(4, 3), (Rgb8{ 30, 20, 10 }));
	// A region of a larger picture (a stride longer than the row).
	cv::Mat big(10, 20, CV_8UC1, cv::Scalar(7));
	big(cv::Rect(2, 2, 5, 3)).setTo(200);
	ASSERT_EQ(writePicturePng(dir / "roi.png", big(cv::Rect(2, 2, 5, 3)), error), 0) << error;
	Gray8Image roi;
	ASSERT_EQ(readGray8Image(dir / "roi.png", roi, error), 0) << error;
	EXPECT_EQ(roi, Gray8Image(5, 3, 200));
}

TEST(ImageCodec, BadShortAndHugeFilesAreRefusedWithClearErrors)
{
	SKIP_WITHOUT_IMAGE_CODECS(); // OpenCV is the reference here
	ScratchDir dir;
	std::string error;
	ASSERT_EQ(writePng(dir / "good.png", pattern(), error), 0) << error;
	std::string good = slurp(dir / "good.png");
	RgbImage out;

	spit(dir / "short.png", good.substr(0, good.size() / 2));
	EXPECT_EQ(readRgbImage(dir / "short.png", out, error), -EINVAL);
	EXPECT_EQ(error.rfind(dir / "short.png: corrupt image data (", 0), 0u) << error;

	std::string flipped = good;
	flipped[good.size() / 2] ^= 0x40; // inside IDAT: its CRC no longer matches
	spit(dir / "crc.png", flipped);
	EXPECT_EQ(readRgbImage(dir / "crc.png", out, error), -EINVAL);
	EXPECT_NE(error.find("corrupt image data"), std::string::npos) << error;

	spit(dir / "text.png", "just text, no picture");
	EXPECT_EQ(readRgbImage(dir / "text.png", out, error), -EINVAL);
	EXPECT_EQ(error, dir / "text.png: not a PNG or JPEG file (or its header is corrupt)");

	ASSERT_TRUE(test::writeHugePng(dir / "huge.png", 20000, 20000));
	EXPECT_EQ(readRgbImage(dir / "huge.png", out, error), -EFBIG);
	EXPECT_EQ(error, dir / "huge.png: 20000x20000 pixels, larger than the 4096x4096 accepted");

	// Busy enough that half the file is well past its header, in the scan.
	cv::Mat bgr(256, 256, CV_8UC3);
	cv::randu(bgr, cv::Scalar::all(0), cv::Scalar::all(255));
	std::string jpeg = encoded(".jpg", bgr);
	spit(dir / "short.jpg", jpeg.substr(0, jpeg.size() / 2));
	EXPECT_EQ(readRgbImage(dir / "short.jpg", out, error), -EINVAL); // never half a picture
	EXPECT_NE(error.find("short.jpg: corrupt image data"), std::string::npos) << error;

	EXPECT_EQ(readRgbImage(dir / "missing.png", out, error), -ENOENT);
	EXPECT_EQ(error.rfind(dir / "missing.png: cannot read", 0), 0u) << error;

	// A 16-bit colour file is no 8-bit picture; a colour file no trimap.
	Gray16Image depth(3, 3, 500);
	ASSERT_EQ(writePng(dir / "depth.png", depth, error), 0) << error;
	EXPECT_EQ(readRgbImage(dir / "depth.png", out, error), -EINVAL);
	EXPECT_EQ(error, dir / "depth.png: must have 8 bits per channel");
	Gray8Image trimap;
	EXPECT_EQ(readGray8Image(dir / "good.png", trimap, error), -EINVAL);
	EXPECT_EQ(error, dir / "good.png: must be a single-channel (grey) 8-bit image, has 3 channels");
}

TEST(ImageCodec, WriteFailuresAreErrorsNamingTheFile)
{
	ScratchDir dir;
	std::string error;
	EXPECT_EQ(writePng(dir / "no/such/folder.png", pattern(), error), -ENOENT);
	EXPECT_EQ(error, dir / "no/such/folder.png: cannot write: No such file or directory");
	EXPECT_EQ(writePng(dir / "empty.png", Gray8Image(), error), -EINVAL);
	EXPECT_EQ(error.rfind(dir / "empty.png: cannot write an empty image", 0), 0u) << error;
	struct stat st;
	EXPECT_NE(stat((dir / "empty.png").c_str(), &st), 0); // nothing left behind
	// /dev/full: every write fails with ENOSPC, as on a full disk.
	EXPECT_EQ(writePng("/dev/full", pattern(), error), -EIO);
	EXPECT_EQ(error.rfind("/dev/full: cannot write", 0), 0u) << error;
}
