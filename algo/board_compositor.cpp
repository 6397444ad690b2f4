#include "algo/board_compositor.hpp"

#include "algo/composite.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace depthkey {

bool BoardCompositor::configure(const Homography &colourToOutput, int colourWidth, int colourHeight,
				int outputWidth, int outputHeight)
{
	clear();
	Homography outputToColour;
	if (colourWidth < 2 || colourHeight < 2 || outputWidth <= 0 || outputHeight <= 0 ||
	    !colourToOutput.inverse(outputToColour))
		return false;
	colourToOutput_ = colourToOutput;
	colourWidth_ = colourWidth;
	colourHeight_ = colourHeight;
	const size_t n = size_t(outputWidth) * outputHeight;
	mapX_.resize(n);
	mapY_.resize(n);
	// Seen: within the colour image's pixel area [-0.5, w - 0.5]. The
	// sample point is clamped so that x0 + 1 and y0 + 1 stay inside (at most
	// 1/256 px off at the last row and column), so the kernel needs no
	// bounds checks.
	const double maxX = (colourWidth - 1) * 256.0 - 1, maxY = (colourHeight - 1) * 256.0 - 1;
	for (int y = 0; y < outputHeight; ++y)
		for (int x = 0; x < outputWidth; ++x) {
			size_t k = size_t(y) * outputWidth + x;
			double sx, sy;
			bool seen = outputToColour.apply(x, y, sx, sy) && sx >= -0.5 && sx <= colourWidth - 0.5 &&
				    sy >= -0.5 && sy <= colourHeight - 0.5;
			mapX_[k] = seen ? int32_t(std::clamp(std::lround(sx * 256.0), 0L, long(maxX))) : kOutside;
			mapY_[k] = seen ? int32_t(std::clamp(std::lround(sy * 256.0), 0L, long(maxY))) : kOutside;
		}
	outputWidth_ = outputWidth;
	outputHeight_ = outputHeight;
	return true;
}

void BoardCompositor::clear()
{
	outputWidth_ = outputHeight_ = colourWidth_ = colourHeight_ = 0;
	mapX_.clear();
	mapY_.clear();
	warped_ = cleared_ = Roi{};
	layerValid_ = false;
}

bool BoardCompositor::sourceOf(int x, int y, int32_t &sxQ8, int32_t &syQ8) const
{
	if (x < 0 || y < 0 || x >= outputWidth_ || y >= outputHeight_)
		return false;
	size_t k = size_t(y) * outputWidth_ + x;
	sxQ8 = mapX_[k];
	syQ8 = mapY_[k];
	return sxQ8 != kOutside;
}

// The board pixels whose bilinear footprint can touch the colour ROI: the
// ROI grown by one pixel (a sample up to a pixel outside reads its edge),
// mapped corner by corner. H maps straight edges to straight edges, so the
// quadrilateral lies within the corners' bounding box.
Roi BoardCompositor::boardRoiOf(const Roi &colourRoi) const
{
	if (colourRoi.empty())
		return {};
	const double x0 = colourRoi.x0 - 1.5, x1 = colourRoi.x1 + 0.5;
	const double y0 = colourRoi.y0 - 1.5, y1 = colourRoi.y1 + 0.5;
	const double cx[4] = { x0, x1, x1, x0 }, cy[4] = { y0, y0, y1, y1 };
	double minU = 1e18, maxU = -1e18, minV = 1e18, maxV = -1e18;
	for (int i = 0; i < 4; ++i) {
		double u, v;
		if (!colourToOutput_.apply(cx[i], cy[i], u, v))
			return { 0, 0, outputWidth_, outputHeight_ }; // beyond the horizon: all of it
		minU = std::min(minU, u);
		maxU = std::max(maxU, u);
		minV = std::min(minV, v);
		maxV = std::max(maxV, v);
	}
	auto clampTo = [](double v, int hi) { return int(std::clamp(v, 0.0, double(hi))); };
	Roi r{ clampTo(std::floor(minU), outputWidth_), clampTo(std::floor(minV), outputHeight_),
	       clampTo(std::ceil(maxU) + 1, outputWidth_), clampTo(std::ceil(maxV) + 1, outputHeight_) };
	return r.empty() ? Roi{} : r;
}

// One output row, x in [x0, x1): bilinear colour and alpha at the mapped
// point (Q8 weights, products Q16), then the camera composite's blend.
void BoardCompositor::warpRow(const RgbImage &colour, const Gray8Image &alpha, const Rgb8 *board, int y,
			      int x0, int x1, int opacityQ8, Rgb8 *composite, Rgba8 *lecturer) const
{
	const int32_t *mx = mapX_.data() + size_t(y) * outputWidth_;
	const int32_t *my = mapY_.data() + size_t(y) * outputWidth_;
	const int stride = colourWidth_;
	const uint8_t *a = alpha.data();
	const Rgb8 *c = colour.data();
	for (int x = x0; x < x1; ++x) {
		const int32_t sx = mx[x];
		if (sx == kOutside) {
			composite[x] = board[x];
			lecturer[x] = { 0, 0, 0, 0 };
			continue;
		}
		const int32_t sy = my[x];
		const size_t k = size_t(sy >> 8) * stride + size_t(sx >> 8);
		const unsigned a00 = a[k], a01 = a[k + 1], a10 = a[k + stride], a11 = a[k + stride + 1];
		if ((a00 | a01 | a10 | a11) == 0) {
			composite[x] = board[x];
			lecturer[x] = { 0, 0, 0, 0 };
			continue;
		}
		const unsigned fx = unsigned(sx) & 255u, fy = unsigned(sy) & 255u;
		const unsigned w00 = (256u - fx) * (256u - fy), w01 = fx * (256u - fy);
		const unsigned w10 = (256u - fx) * fy, w11 = fx * fy; // sum 65536
		auto mix = [&](unsigned v00, unsigned v01, unsigned v10, unsigned v11) {
			return (v00 * w00 + v01 * w01 + v10 * w10 + v11 * w11 + 32768u) >> 16;
		};
		const Rgb8 c00 = c[k], c01 = c[k + 1], c10 = c[k + stride], c11 = c[k + stride + 1];
		const unsigned al = mix(a00, a01, a10, a11);
		const unsigned r = mix(c00.r, c01.r, c10.r, c11.r), g = mix(c00.g, c01.g, c10.g, c11.g),
			       b = mix(c00.b, c01.b, c10.b, c11.b);
		const unsigned w = compositeWeight(opacityQ8, uint8_t(al)), wb = 256u - w;
		composite[x] = { uint8_t((board[x].r * wb + r * w + 128u) >> 8), uint8_t((board[x].g * wb + g * w + 128u) >> 8),
				 uint8_t((board[x].b * wb + b * w + 128u) >> 8) };
		lecturer[x] = { uint8_t(r), uint8_t(g), uint8_t(b), uint8_t(al) };
	}
}

void BoardCompositor::compose(const RgbImage &colour, const Gray8Image &alpha, const Roi &roi,
			      const RgbImage &board, int opacityQ8, RgbImage &composite, RgbaImage &lecturer)
{
	const int w = outputWidth_, h = outputHeight_;
	composite.resize(w, h);
	lecturer.resize(w, h);
	if (!configured() || colour.width() != colourWidth_ || colour.height() != colourHeight_ ||
	    alpha.width() != colourWidth_ || alpha.height() != colourHeight_ || board.width() != w ||
	    board.height() != h) {
		// Sizes that do not fit the map: the board alone (the caller
		// reconfigures; this never reads out of bounds).
		if (board.width() == w && board.height() == h)
			std::memcpy(composite.data(), board.data(), composite.size() * sizeof(Rgb8));
		std::fill(lecturer.data(), lecturer.data() + lecturer.size(), Rgba8{ 0, 0, 0, 0 });
		layerValid_ = false;
		return;
	}
	const Roi clampedRoi{ std::max(roi.x0, 0), std::max(roi.y0, 0), std::min(roi.x1, colourWidth_),
			      std::min(roi.y1, colourHeight_) };
	warped_ = boardRoiOf(clampedRoi);
	// The layer is transparent outside what was written last time: clear
	// only that (a whole 1920x1080 RGBA clear would cost as much as the warp).
	if (!layerValid_) {
		std::fill(lecturer.data(), lecturer.data() + lecturer.size(), Rgba8{ 0, 0, 0, 0 });
		layerValid_ = true;
	} else {
		for (int y = cleared_.y0; y < cleared_.y1; ++y)
			std::memset(lecturer.row(y) + cleared_.x0, 0, size_t(cleared_.x1 - cleared_.x0) * sizeof(Rgba8));
	}
	cleared_ = warped_;
	const int y0 = warped_.empty() ? h : warped_.y0, y1 = warped_.empty() ? h : warped_.y1;
	const int x0 = warped_.x0, x1 = warped_.x1;
	std::memcpy(composite.row(0), board.row(0), size_t(y0) * w * sizeof(Rgb8));
	std::memcpy(composite.row(y1), board.row(y1), size_t(h - y1) * w * sizeof(Rgb8));
	for (int y = y0; y < y1; ++y) {
		Rgb8 *dst = composite.row(y);
		const Rgb8 *b = board.row(y);
		std::memcpy(dst, b, size_t(x0) * sizeof(Rgb8));
		warpRow(colour, alpha, b, y, x0, x1, opacityQ8, dst, lecturer.row(y));
		std::memcpy(dst + x1, b + x1, size_t(w - x1) * sizeof(Rgb8));
	}
}

} // namespace depthkey
