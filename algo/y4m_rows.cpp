#include "algo/y4m_rows.hpp"

#include <cmath>
#include <initializer_list>
#include <numeric>

namespace depthkey {

namespace {

inline uint8_t clampByte(int v)
{
	return static_cast<uint8_t>(v > 255 ? 255 : v);
}

} // namespace

// Full-range BT.601 (JFIF), coefficients scaled by 2^16 and rounded so that
// each row sums exactly: Y = 0.299 R + 0.587 G + 0.114 B -> 19595, 38470,
// 7471 (sum 65536, so white is exactly 255); Cb = -0.168736 R - 0.331264 G +
// 0.5 B -> -11058, -21710, 32768 (sum 0, so greys have Cb = 128 exactly);
// Cr = 0.5 R - 0.418688 G - 0.081312 B -> 32768, -27439, -5329 (sum 0).
// The +32768 rounds to nearest; Cb/Cr can reach 256 for pure blue/red.
void rgbToYuv444Row_C(const uint8_t *src, int width, int bpp, uint8_t *y, uint8_t *u,
		      uint8_t *v, uint8_t *a)
{
	constexpr int kHalf = 1 << 15;
	constexpr int kChromaOffset = 128 << 16;
	for (int x = 0; x < width; x++, src += bpp) {
		const int r = src[0], g = src[1], b = src[2];
		y[x] = static_cast<uint8_t>((19595 * r + 38470 * g + 7471 * b + kHalf) >> 16);
		u[x] = clampByte((-11058 * r - 21710 * g + 32768 * b + kChromaOffset + kHalf) >> 16);
		v[x] = clampByte((32768 * r - 27439 * g - 5329 * b + kChromaOffset + kHalf) >> 16);
		if (a)
			a[x] = src[3];
	}
}

// The mean of four samples, +2 rounds half up: the chroma sits at the centre
// of the 2x2 block, which y4m calls "420jpeg".
void subsampleChromaRow_C(const uint8_t *row0, const uint8_t *row1, int width, uint8_t *dst)
{
	int x = 0;
	for (; x + 1 < width; x += 2)
		dst[x / 2] = static_cast<uint8_t>((row0[x] + row0[x + 1] + row1[x] + row1[x + 1] + 2) >> 2);
	if (x < width)
		dst[x / 2] = static_cast<uint8_t>((2 * row0[x] + 2 * row1[x] + 2) >> 2);
}

FrameRate y4mFrameRate(double fps)
{
	if (!(fps >= kMinFrameRate))
		fps = kMinFrameRate;
	if (fps > kMaxFrameRate)
		fps = kMaxFrameRate;
	// Cameras that say 30 often deliver 30000/1001: keep the broadcast form.
	for (uint32_t base : { 24u, 30u, 60u }) {
		const double ntsc = base * 1000.0 / 1001.0;
		if (std::fabs(fps - ntsc) <= ntsc * 0.001 && std::fabs(fps - base) > base * 0.0002)
			return { base * 1000, 1001 };
	}
	const double whole = std::round(fps);
	if (whole >= 1 && std::fabs(fps - whole) <= fps * 0.005)
		return { static_cast<uint32_t>(whole), 1 };
	// fps <= 1000, so the numerator is at most 10^6: no overflow.
	const uint32_t milli = static_cast<uint32_t>(std::lround(fps * 1000.0));
	const uint32_t common = std::gcd(milli, 1000u);
	return { milli / common, 1000 / common };
}

} // namespace depthkey
