// Fixed-point pixel converters against double-precision references.
// Tolerances: YUV->RGB within 1 level per channel (Q14 coefficients, one
// rounding); 16-bit depth->mm within 1 mm (Q16 scale, one rounding).
#include <gtest/gtest.h>

#include "hal/v4l2/depth16_to_frame.hpp"
#include "hal/v4l2/yuv_to_rgb.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <vector>

using namespace depthkey;

namespace {

int referenceChannel(double v)
{
	return static_cast<int>(std::lround(std::clamp(v, 0.0, 255.0)));
}

// BT.601 limited range in doubles, from the standard's constants.
Rgb8 referenceYuv(int y, int u, int v)
{
	double yy = (y - 16) * 255.0 / 219.0;
	double cb = (u - 128) * 255.0 / 224.0, cr = (v - 128) * 255.0 / 224.0;
	return { static_cast<uint8_t>(referenceChannel(yy + 1.402 * cr)),
		 static_cast<uint8_t>(referenceChannel(yy - 0.344136 * cb - 0.714136 * cr)),
		 static_cast<uint8_t>(referenceChannel(yy + 1.772 * cb)) };
}

} // namespace

TEST(YuvToRgb, EveryYuvTripletWithinOneLevelOfDouble)
{
	long histogram[256] = {};
	int worst = 0;
	for (int y = 0; y < 256; y++)
		for (int u = 0; u < 256; u++)
			for (int v = 0; v < 256; v++) {
				Rgb8 got = yuvToRgbPixel(y, u, v), want = referenceYuv(y, u, v);
				int e = std::max({ std::abs(got.r - want.r), std::abs(got.g - want.g),
						   std::abs(got.b - want.b) });
				histogram[e]++;
				worst = std::max(worst, e);
			}
	std::printf("YUV->RGB max channel error histogram: 0: %ld, 1: %ld, >1: %ld\n",
		    histogram[0], histogram[1], 16777216L - histogram[0] - histogram[1]);
	EXPECT_LE(worst, 1);
	EXPECT_EQ(yuvToRgbPixel(16, 128, 128), (Rgb8{ 0, 0, 0 }));
	EXPECT_EQ(yuvToRgbPixel(235, 128, 128), (Rgb8{ 255, 255, 255 }));
}

TEST(YuvToRgb, YuyvFrameUsesEachPairsChromaAndHandlesOddWidthAndStride)
{
	// 3x2 pixels, stride 12 (two pixel pairs per row: the last pair half used).
	const int w = 3, h = 2, stride = 12;
	std::vector<uint8_t> buf(stride * h, 0);
	for (int row = 0; row < h; row++) {
		uint8_t *p = buf.data() + row * stride;
		uint8_t line[8] = { 50, 90, 100, 200, 150, 60, 220, 140 }; // Y0 U Y1 V Y2 U Y3 V
		std::copy(line, line + 8, p);
	}
	RgbImage out;
	ASSERT_EQ(yuyvToRgb(buf.data(), buf.size(), w, h, stride, out), 0);
	EXPECT_EQ(out.at(0, 1), yuvToRgbPixel(50, 90, 200));
	EXPECT_EQ(out.at(1, 1), yuvToRgbPixel(100, 90, 200));
	EXPECT_EQ(out.at(2, 1), yuvToRgbPixel(150, 60, 140));
	EXPECT_EQ(yuyvToRgb(buf.data(), stride + 7, w, h, stride, out), -EMSGSIZE);
	EXPECT_EQ(yuyvToRgb(buf.data(), buf.size(), w, h, 4, out), -EMSGSIZE);
}

TEST(YuvToRgb, Nv12FrameSharesChromaBetweenRowPairs)
{
	const int w = 4, h = 4, stride = 4;
	std::vector<uint8_t> buf(stride * h + stride * h / 2);
	for (int i = 0; i < w * h; i++)
		buf[i] = static_cast<uint8_t>(20 + i * 10);
	uint8_t chroma[8] = { 100, 150, 60, 200, 120, 130, 240, 16 };
	std::copy(chroma, chroma + 8, buf.begin() + w * h);
	RgbImage out;
	ASSERT_EQ(nv12ToRgb(buf.data(), buf.size(), w, h, stride, out), 0);
	EXPECT_EQ(out.at(0, 0), yuvToRgbPixel(20, 100, 150));
	EXPECT_EQ(out.at(3, 1), yuvToRgbPixel(20 + 7 * 10, 60, 200));
	EXPECT_EQ(out.at(1, 2), yuvToRgbPixel(20 + 9 * 10, 120, 130));
	EXPECT_EQ(out.at(2, 3), yuvToRgbPixel(20 + 14 * 10, 240, 16));
	EXPECT_EQ(nv12ToRgb(buf.data(), w * h + 5, w, h, stride, out), -EMSGSIZE);
}

TEST(Depth16ToFrame, ScaledDepthWithinOneMillimetreOfDouble)
{
	for (double scale : { 1.0, 0.125, 0.1, 0.25, 2.5, 7500.0 / 65536.0, 99.99 }) {
		uint32_t q = depthScaleQ16(scale);
		int worst = 0;
		std::vector<uint8_t> row(2 * 65536);
		for (int raw = 0; raw < 65536; raw++) {
			row[2 * raw] = raw & 0xff;
			row[2 * raw + 1] = raw >> 8;
		}
		std::vector<uint16_t> mm(65536);
		depth16ToMmRow(row.data(), mm.data(), 65536, q, 0, 65535);
		for (int raw = 1; raw < 65536; raw++) {
			double want = raw * scale;
			if (want > 65535)
				break;
			worst = std::max(worst, static_cast<int>(std::abs(mm[raw] - std::lround(want))));
		}
		EXPECT_LE(worst, 1) << "scale " << scale;
		EXPECT_EQ(mm[0], 0) << "raw 0 is no measurement";
	}
}

TEST(Depth16ToFrame, RangeStrideAndShortBuffers)
{
	const int w = 3, h = 2, stride = 8;
	std::vector<uint8_t> buf(stride * h, 0);
	uint16_t values[3] = { 299, 1000, 7501 };
	for (int row = 0; row < h; row++)
		for (int x = 0; x < w; x++) {
			buf[row * stride + 2 * x] = values[x] & 0xff;
			buf[row * stride + 2 * x + 1] = values[x] >> 8;
		}
	DepthFrame frame;
	ASSERT_EQ(depth16ToFrame(buf.data(), buf.size(), w, h, stride, depthScaleQ16(1.0), 300, 7500,
				 frame), 0);
	EXPECT_EQ(frame.depthMm.at(0, 1), 0);
	EXPECT_EQ(frame.depthMm.at(1, 1), 1000);
	EXPECT_EQ(frame.depthMm.at(2, 1), 0);
	EXPECT_EQ(frame.amplitude.at(1, 1), 0xFFFF);
	EXPECT_EQ(frame.amplitude.at(0, 1), 0);
	EXPECT_EQ(depth16ToFrame(buf.data(), stride + 5, w, h, stride, 65536, 300, 7500, frame),
		  -EMSGSIZE);
}
