#include "hal/v4l2/yuv_to_rgb.hpp"

#include <cerrno>

namespace depthkey {

namespace {

// BT.601 limited range, coefficients in Q14 (x 16384, rounded):
//   luma  255/219                 = 1.164384 -> 19077
//   R: Cr 1.402 * 255/224         = 1.596027 -> 26149
//   G: Cb 0.344136 * 255/224      = 0.391762 ->  6419
//   G: Cr 0.714136 * 255/224      = 0.812968 -> 13320
//   B: Cb 1.772 * 255/224         = 2.017232 -> 33050
// Worst case |sum| < 2^14 * 600 < 2^24: int is plenty. + 2^13 rounds.
constexpr int kShift = 14;
constexpr int kRound = 1 << (kShift - 1);
constexpr int kY = 19077;
constexpr int kRv = 26149;
constexpr int kGu = 6419;
constexpr int kGv = 13320;
constexpr int kBu = 33050;

uint8_t clampByte(int v)
{
	return static_cast<uint8_t>(v < 0 ? 0 : v > 255 ? 255 : v);
}

} // namespace

Rgb8 yuvToRgbPixel(int y, int u, int v)
{
	int luma = (y - 16) * kY + kRound;
	int cb = u - 128, cr = v - 128;
	return { clampByte((luma + kRv * cr) >> kShift),
		 clampByte((luma - kGu * cb - kGv * cr) >> kShift),
		 clampByte((luma + kBu * cb) >> kShift) };
}

void yuyvToRgbRow(const uint8_t *yuyv, Rgb8 *rgb, int width)
{
	int x = 0;
	for (; x + 1 < width; x += 2, yuyv += 4) {
		rgb[x] = yuvToRgbPixel(yuyv[0], yuyv[1], yuyv[3]);
		rgb[x + 1] = yuvToRgbPixel(yuyv[2], yuyv[1], yuyv[3]);
	}
	if (x < width)
		rgb[x] = yuvToRgbPixel(yuyv[0], yuyv[1], yuyv[3]);
}

void nv12ToRgbRow(const uint8_t *y, const uint8_t *uv, Rgb8 *rgb, int width)
{
	for (int x = 0; x < width; x++)
		rgb[x] = yuvToRgbPixel(y[x], uv[x & ~1], uv[(x & ~1) + 1]);
}

int yuyvToRgb(const uint8_t *data, size_t bytes, int width, int height, size_t bytesPerLine,
	      RgbImage &out)
{
	size_t rowBytes = static_cast<size_t>((width + 1) / 2) * 4;
	if (bytesPerLine < rowBytes || height <= 0 ||
	    bytes < bytesPerLine * static_cast<size_t>(height - 1) + rowBytes)
		return -EMSGSIZE;
	out.resize(width, height);
	for (int y = 0; y < height; y++)
		yuyvToRgbRow(data + bytesPerLine * static_cast<size_t>(y), out.row(y), width);
	return 0;
}

int nv12ToRgb(const uint8_t *data, size_t bytes, int width, int height, size_t bytesPerLine,
	      RgbImage &out)
{
	size_t rowBytes = static_cast<size_t>(width + 1) & ~size_t(1); // UV row: pairs
	size_t chromaRows = static_cast<size_t>(height + 1) / 2;
	size_t lumaBytes = bytesPerLine * static_cast<size_t>(height);
	if (bytesPerLine < rowBytes || height <= 0 ||
	    bytes < lumaBytes + bytesPerLine * (chromaRows - 1) + rowBytes)
		return -EMSGSIZE;
	out.resize(width, height);
	const uint8_t *chroma = data + lumaBytes;
	for (int y = 0; y < height; y++)
		nv12ToRgbRow(data + bytesPerLine * static_cast<size_t>(y),
			     chroma + bytesPerLine * static_cast<size_t>(y / 2), out.row(y), width);
	return 0;
}

} // namespace depthkey
