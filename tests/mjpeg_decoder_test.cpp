// MJPEG decoding: a JPEG made here with TurboJPEG comes back within JPEG's
// loss; truncated, garbage and wrong-size JPEGs are refused.
#include <gtest/gtest.h>

#include "hal/v4l2/mjpeg_decoder.hpp"

#include <cerrno>
#include <cstdlib>
#include <turbojpeg.h>
#include <vector>

using namespace depthkey;

namespace {

std::vector<uint8_t> encode(const RgbImage &image)
{
	tjhandle tj = tjInitCompress();
	unsigned char *jpeg = nullptr;
	unsigned long size = 0;
	int ret = tjCompress2(tj, reinterpret_cast<const unsigned char *>(image.data()),
			      image.width(), image.width() * 3, image.height(), TJPF_RGB, &jpeg,
			      &size, TJSAMP_422, 95, 0);
	std::vector<uint8_t> out;
	if (ret == 0)
		out.assign(jpeg, jpeg + size);
	tjFree(jpeg);
	tjDestroy(tj);
	return out;
}

RgbImage gradient(int w, int h)
{
	RgbImage image(w, h);
	for (int y = 0; y < h; y++)
		for (int x = 0; x < w; x++)
			image.at(x, y) = { static_cast<uint8_t>(x * 4), static_cast<uint8_t>(y * 4), 128 };
	return image;
}

} // namespace

TEST(MjpegDecoder, DecodesWithinJpegLoss)
{
	RgbImage in = gradient(64, 48);
	std::vector<uint8_t> jpeg = encode(in);
	ASSERT_FALSE(jpeg.empty());
	MjpegDecoder decoder;
	RgbImage out;
	ASSERT_EQ(decoder.decode(jpeg.data(), jpeg.size(), 64, 48, out), 0) << decoder.lastError();
	int worst = 0;
	for (int y = 0; y < 48; y++)
		for (int x = 0; x < 64; x++) {
			Rgb8 a = in.at(x, y), b = out.at(x, y);
			worst = std::max({ worst, std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b) });
		}
	EXPECT_LE(worst, 12); // quality 95, 4:2:2, fast DCT on a smooth gradient
}

TEST(MjpegDecoder, RefusesTruncatedGarbageAndWrongSize)
{
	std::vector<uint8_t> jpeg = encode(gradient(64, 48));
	MjpegDecoder decoder;
	RgbImage out;
	EXPECT_EQ(decoder.decode(jpeg.data(), jpeg.size() / 2, 64, 48, out), -EBADMSG);
	std::vector<uint8_t> garbage(1000, 0x5a);
	EXPECT_EQ(decoder.decode(garbage.data(), garbage.size(), 64, 48, out), -EBADMSG);
	EXPECT_EQ(decoder.decode(jpeg.data(), 0, 64, 48, out), -EBADMSG);
	EXPECT_EQ(decoder.decode(jpeg.data(), jpeg.size(), 640, 480, out), -EINVAL);
	EXPECT_NE(decoder.lastError(), "");
}
