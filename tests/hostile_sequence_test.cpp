// Regression tests of issue 14 for the sequence reader of the replay backend
// and depthkey-eval (hal/recording/sequence_reader.hpp): an image whose
// header claims more pixels than any configured frame is refused before it
// is decoded (case G), and an index file or image that is a FIFO is refused
// without blocking (case H).
#include "hal/image_file.hpp"
#include "hal/image_file_reader.hpp"
#include "hal/recording/sequence_reader.hpp"
#include "tests/hostile_files.hpp"
#include "tests/huge_png.hpp"
#include "tests/image_codecs.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <opencv2/imgcodecs.hpp>
#include <sys/stat.h>

using namespace depthkey;
using depthkey::test::FifoWithWriter;
using depthkey::test::ScratchDir;

namespace {

// A PNG of one colour by the project's own encoder (hal/png_codec, checked
// against OpenCV's in image_codec_test), so that these tests run where the
// build has no OpenCV codecs too (ARCH=arm64: DEPTHKEY_NO_IMGCODECS).
std::string pngBytes(int width, int height)
{
	ScratchDir dir;
	std::string error;
	if (writePng(dir / "picture.png", RgbImage(width, height, Rgb8{ 30, 20, 10 }), error) < 0)
		return {};
	std::ifstream in(dir / "picture.png", std::ios::binary);
	return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

} // namespace

TEST(HostileSequence, HugePngIsRefusedFromItsHeader)
{
	ScratchDir dir;
	mkdir((dir / "rgb").c_str(), 0755);
	ASSERT_TRUE(test::writeHugePng(dir / "rgb/000001.png", 20000, 20000));
	struct stat st{};
	ASSERT_EQ(stat((dir / "rgb/000001.png").c_str(), &st), 0);
	EXPECT_LT(st.st_size, 1 << 20); // small on disk, 400 Mpx inside
	std::ofstream(dir / "rgb.txt") << "1.000000000 rgb/000001.png\n";

	SequenceReader reader;
	ASSERT_EQ(reader.open(dir.path()), 0) << reader.describeError();
	ColourFrame colour;
	EXPECT_EQ(reader.readColour(0, colour), -EFBIG);
	EXPECT_EQ(reader.describeError(),
		  dir / "rgb/000001.png" + ": 20000x20000 pixels, larger than the 1920x1080 accepted");
	EXPECT_TRUE(colour.rgb.empty());

	// A frame of the largest configurable size is still read.
	std::ofstream(dir / "rgb/000001.png") << pngBytes(1920, 1080);
	ASSERT_EQ(reader.readColour(0, colour), 0) << reader.describeError();
	EXPECT_EQ(colour.rgb.width(), 1920);
}

TEST(HostileSequence, FifoIndexOrImageIsRefusedWithoutBlocking)
{
	ScratchDir dir;
	{
		FifoWithWriter fifo(dir / "rgb.txt", "1.000000000 rgb/000001.png\n");
		ASSERT_TRUE(fifo.ok());
		SequenceReader reader;
		EXPECT_EQ(reader.open(dir.path()), -EINVAL);
		EXPECT_EQ(reader.describeError(), dir / "rgb.txt" + ": cannot read: not a regular file (a FIFO)");
	}
	unlink((dir / "rgb.txt").c_str());
	std::ofstream(dir / "rgb.txt") << "1.000000000 rgb/000001.png\n";
	mkdir((dir / "rgb").c_str(), 0755);
	FifoWithWriter fifo(dir / "rgb/000001.png", pngBytes(16, 16));
	ASSERT_TRUE(fifo.ok());
	SequenceReader reader;
	ASSERT_EQ(reader.open(dir.path()), 0);
	ColourFrame colour;
	EXPECT_EQ(reader.readColour(0, colour), -EINVAL);
	EXPECT_EQ(reader.describeError(), dir / "rgb/000001.png" + ": cannot read: not a regular file (a FIFO)");
}

TEST(ImageHeader, SizesOfPngAndJpegWithoutDecoding)
{
	SKIP_WITHOUT_IMAGE_CODECS();
	std::string png = pngBytes(37, 21);
	int w = 0, h = 0;
	ASSERT_TRUE(imageHeaderSize(reinterpret_cast<const unsigned char *>(png.data()), png.size(), w, h));
	EXPECT_EQ(w, 37);
	EXPECT_EQ(h, 21);
	std::vector<uchar> jpeg;
	cv::imencode(".jpg", cv::Mat(13, 29, CV_8UC3, cv::Scalar(1, 2, 3)), jpeg);
	ASSERT_TRUE(imageHeaderSize(jpeg.data(), jpeg.size(), w, h));
	EXPECT_EQ(w, 29);
	EXPECT_EQ(h, 13);
	const unsigned char junk[] = "P6\n3 3\n255\n";
	EXPECT_FALSE(imageHeaderSize(junk, sizeof(junk), w, h));
	EXPECT_FALSE(imageHeaderSize(reinterpret_cast<const unsigned char *>(png.data()), 20, w, h));
}
