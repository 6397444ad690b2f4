#include "algo/composite.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace depthkey {

int opacityToQ8(double opacity)
{
	if (!(opacity > 0.0))
		return 0;
	if (opacity >= 1.0)
		return 256;
	return static_cast<int>(std::lround(opacity * 256.0));
}

void compositeRow_C(const Rgb8 *lecturer, const uint8_t *alpha, const Rgb8 *board,
		    int opacityQ8, Rgb8 *out, int width)
{
	for (int x = 0; x < width; ++x) {
		unsigned w = compositeWeight(opacityQ8, alpha[x]); // 0..256
		unsigned wb = 256u - w;
		out[x].r = static_cast<uint8_t>((board[x].r * wb + lecturer[x].r * w + 128u) >> 8);
		out[x].g = static_cast<uint8_t>((board[x].g * wb + lecturer[x].g * w + 128u) >> 8);
		out[x].b = static_cast<uint8_t>((board[x].b * wb + lecturer[x].b * w + 128u) >> 8);
	}
}

void lecturerLayerRow_C(const Rgb8 *colour, const uint8_t *alpha, Rgba8 *out, int width)
{
	for (int x = 0; x < width; ++x)
		out[x] = { colour[x].r, colour[x].g, colour[x].b, alpha[x] };
}

void compositeRow(KernelPath path, const Rgb8 *lecturer, const uint8_t *alpha, const Rgb8 *board,
		  int opacityQ8, Rgb8 *out, int width)
{
	if (sse2Rows(path))
		compositeRow_SSE2(lecturer, alpha, board, opacityQ8, out, width);
	else if (path == KernelPath::Neon)
		compositeRow_NEON(lecturer, alpha, board, opacityQ8, out, width);
	else
		compositeRow_C(lecturer, alpha, board, opacityQ8, out, width);
}

void lecturerLayerRow(KernelPath path, const Rgb8 *colour, const uint8_t *alpha, Rgba8 *out, int width)
{
	if (sse2Rows(path))
		lecturerLayerRow_SSE2(colour, alpha, out, width);
	else if (path == KernelPath::Neon)
		lecturerLayerRow_NEON(colour, alpha, out, width);
	else
		lecturerLayerRow_C(colour, alpha, out, width);
}

void composite(const RgbImage &lecturer, const Gray8Image &alpha, const RgbImage &board,
	       int opacityQ8, RgbImage &out, KernelPath path)
{
	out.resize(lecturer.width(), lecturer.height());
	for (int y = 0; y < lecturer.height(); ++y)
		compositeRow(path, lecturer.row(y), alpha.row(y), board.row(y), opacityQ8, out.row(y),
			     lecturer.width());
}

void compositeRoi(const RgbImage &lecturer, const Gray8Image &alpha, const RgbImage &board, const Roi &roi,
		  int opacityQ8, RgbImage &out, KernelPath path)
{
	const int w = lecturer.width(), h = lecturer.height();
	out.resize(w, h);
	if (w == 0 || h == 0)
		return;
	const CompositeInputs in{ &lecturer, &alpha, &board, roi, opacityQ8, path };
	for (int y = 0; y < h; ++y)
		compositeRoiRow(in, y, out.row(y));
}

void compositeRoiRow(const CompositeInputs &in, int y, Rgb8 *out)
{
	const int w = in.width(), h = in.height();
	const Roi &roi = in.roi;
	const int y0 = roi.empty() ? h : std::clamp(roi.y0, 0, h), y1 = roi.empty() ? h : std::clamp(roi.y1, y0, h);
	const int x0 = std::clamp(roi.x0, 0, w), x1 = std::clamp(roi.x1, x0, w);
	// A board one row high is that row everywhere (a solid colour).
	const Rgb8 *b = in.board->row(in.board->height() == 1 ? 0 : y);
	if (y < y0 || y >= y1) { // outside the ROI the alpha is 0: the board
		std::memcpy(out, b, size_t(w) * sizeof(Rgb8));
		return;
	}
	std::memcpy(out, b, size_t(x0) * sizeof(Rgb8));
	compositeRow(in.path, in.lecturer->row(y) + x0, in.alpha->row(y) + x0, b + x0, in.opacityQ8, out + x0,
		     x1 - x0);
	std::memcpy(out + x1, b + x1, size_t(w - x1) * sizeof(Rgb8));
}

void lecturerLayer(const RgbImage &colour, const Gray8Image &alpha, RgbaImage &out, KernelPath path)
{
	out.resize(colour.width(), colour.height());
	for (int y = 0; y < colour.height(); ++y)
		lecturerLayerRow(path, colour.row(y), alpha.row(y), out.row(y), colour.width());
}

} // namespace depthkey
