#include "algo/board_pattern.hpp"

#include <algorithm>
#include <cmath>

namespace depthkey {

double BoardPattern::spacingPx() const
{
	double sx = fill * boardWidth / std::max(1, grid.cols - 1);
	double sy = fill * boardHeight / std::max(1, grid.rows - 1);
	return std::floor(std::min(sx, sy));
}

ImagePoint BoardPattern::centre(int i) const
{
	const double s = spacingPx();
	// Centred on the screen's middle, (W - 1) / 2 with pixel centres at i.
	const double x0 = (boardWidth - 1) / 2.0 - s * (grid.cols - 1) / 2.0;
	const double y0 = (boardHeight - 1) / 2.0 - s * (grid.rows - 1) / 2.0;
	return { x0 + s * (i % grid.cols), y0 + s * (i / grid.cols) };
}

std::vector<ImagePoint> BoardPattern::centres() const
{
	std::vector<ImagePoint> out;
	for (int i = 0; i < grid.count(); ++i)
		out.push_back(centre(i));
	return out;
}

double BoardPattern::darkness(double u, double v, double footprintPx) const
{
	const double s = spacingPx();
	const ImagePoint first = centre(0);
	int i = std::clamp(int(std::lround((u - first.x) / s)), 0, grid.cols - 1);
	int j = std::clamp(int(std::lround((v - first.y) / s)), 0, grid.rows - 1);
	double d = std::hypot(u - (first.x + i * s), v - (first.y + j * s));
	return std::clamp((radiusPx() - d) / std::max(footprintPx, 1e-3) + 0.5, 0.0, 1.0);
}

void BoardPattern::render(RgbImage &out) const
{
	out.resize(boardWidth, boardHeight);
	for (int y = 0; y < boardHeight; ++y)
		for (int x = 0; x < boardWidth; ++x) {
			uint8_t level = uint8_t(std::lround(255.0 * (1.0 - darkness(x, y, 1.0))));
			out.at(x, y) = { level, level, level };
		}
}

} // namespace depthkey
