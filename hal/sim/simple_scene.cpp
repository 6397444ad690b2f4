#include "hal/sim/simple_scene.hpp"

#include <cmath>

namespace depthkey {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Cheap deterministic per-pixel noise (a hash, not a generator), so rendering
// a frame twice gives the same pixels.
uint32_t hash(uint64_t a, uint64_t b)
{
	uint64_t x = a * 0x9E3779B97F4A7C15ull ^ (b + 0x632BE59BD9B4E019ull);
	x ^= x >> 31;
	x *= 0xBF58476D1CE4E5B9ull;
	x ^= x >> 29;
	return static_cast<uint32_t>(x);
}

} // namespace

bool SimpleScene::figureAt(double timeS, double u, double v) const
{
	// Walks across the middle 60 % of the view, once every 8 s.
	double centre = 0.5 + 0.3 * std::sin(2.0 * kPi * timeS / 8.0 + static_cast<double>(seed_ % 7));
	double dx = u - centre;
	double headDy = v - 0.28;
	if (dx * dx * 16.0 / 9.0 + headDy * headDy < 0.09 * 0.09)
		return true;
	return std::fabs(dx) < 0.11 && v > 0.36 && v < 1.0;
}

void SimpleScene::renderColour(double timeS, RgbImage &out) const
{
	const int w = out.width(), h = out.height();
	uint64_t frameKey = static_cast<uint64_t>(timeS * 1000.0);
	for (int y = 0; y < h; ++y) {
		Rgb8 *row = out.row(y);
		double v = (y + 0.5) / h;
		for (int x = 0; x < w; ++x) {
			double u = (x + 0.5) / w;
			Rgb8 px;
			if (figureAt(timeS, u, v))
				px = v < 0.36 ? Rgb8{ 224, 172, 140 } : Rgb8{ 150, 40, 50 };
			else if (std::fabs(v - 0.5 - 0.05 * std::sin(u * 20.0)) < 0.004)
				px = Rgb8{ 235, 235, 230 }; // a chalk stroke
			else
				px = Rgb8{ 30, 60, 40 };
			int n = static_cast<int>(hash(frameKey, static_cast<uint64_t>(y) * w + x) % 9) - 4;
			auto noisy = [n](uint8_t c) {
				int value = c + n;
				return static_cast<uint8_t>(value < 0 ? 0 : value > 255 ? 255 : value);
			};
			row[x] = { noisy(px.r), noisy(px.g), noisy(px.b) };
		}
	}
}

void SimpleScene::renderDepth(double timeS, DepthFrame &out) const
{
	const int w = out.depthMm.width(), h = out.depthMm.height();
	uint64_t frameKey = static_cast<uint64_t>(timeS * 1000.0) + 1;
	for (int y = 0; y < h; ++y) {
		double v = (y + 0.5) / h;
		for (int x = 0; x < w; ++x) {
			double u = (x + 0.5) / w;
			bool figure = figureAt(timeS, u, v);
			int noise = static_cast<int>(hash(frameKey, static_cast<uint64_t>(y) * w + x) % 41) - 20;
			out.depthMm.at(x, y) = static_cast<uint16_t>((figure ? kFigureDepthMm : kBoardDepthMm) + noise);
			out.amplitude.at(x, y) = figure ? 9000 : 4000;
			out.intensity.at(x, y) = figure ? 16000 : 12000;
		}
	}
}

} // namespace depthkey
