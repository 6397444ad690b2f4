// Synthetic still images with a known answer, for SIOX tests and benchmarks:
// a chalkboard (dark green, chalk strokes, a yellow stroke) with a lecturer
// (skin head and hands, a shirt, an arm reaching out with a hand joined by a
// thin wrist), anti-aliased edges (2x2 supersampling: the boundary pixels are
// mixed, as a camera's are) and sensor noise. The trimap is what depth seeds
// give: surely lecturer = truth eroded, surely board = outside the truth
// dilated, so the undecided band is `band` pixels wide around the true edge.
#pragma once

#include "algo/image.hpp"
#include "algo/morphology.hpp"
#include "algo/trimap.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>

namespace depthkey::test {

struct SyntheticStill {
	RgbImage image;
	Gray8Image truth;   // 255 = lecturer (pixel centre inside)
	Gray8Image trimap;
};

struct StillStyle {
	Rgb8 board{ 30, 60, 40 };
	Rgb8 chalk{ 235, 235, 230 };
	Rgb8 yellow{ 230, 200, 60 };
	Rgb8 shirt{ 150, 40, 50 };
	Rgb8 skin{ 224, 172, 140 };
	int noise = 6; // +- code values, uniform
};

// Fraction-free shape test in normalised coordinates (u, v in [0, 1)).
inline int stillShape(double u, double v, double shift)
{
	double cx = 0.5 + shift;
	double dx = u - cx, hy = v - 0.25;
	if (dx * dx / (0.07 * 0.07) + hy * hy / (0.09 * 0.09) < 1.0)
		return 2; // head (skin)
	if (std::fabs(dx) < 0.14 && v > 0.35)
		return 1; // torso (shirt)
	if (u > cx + 0.13 && u < cx + 0.30 && std::fabs(v - 0.5) < 0.035)
		return 1; // arm (shirt)
	if (u >= cx + 0.30 && u < cx + 0.31 && std::fabs(v - 0.5) < 0.012)
		return 2; // thin wrist
	double hx = u - (cx + 0.345), hv = v - 0.5;
	if (hx * hx + hv * hv < 0.035 * 0.035)
		return 2; // hand
	return 0;
}

inline SyntheticStill makeStill(int w, int h, int band, uint32_t seed, const StillStyle &style = {})
{
	SyntheticStill s;
	s.image.resize(w, h);
	s.truth.resize(w, h);
	std::mt19937 rng(seed);
	std::uniform_int_distribution<int> noise(-style.noise, style.noise);
	double shift = (seed % 5) * 0.02 - 0.04;
	auto boardAt = [&](double u, double v) {
		if (std::fabs(v - 0.30 - 0.04 * std::sin(u * 25.0 + seed)) < 0.006)
			return style.chalk;
		if (std::fabs(u - 0.15 - 0.03 * std::sin(v * 17.0)) < 0.005)
			return style.yellow;
		return style.board;
	};
	for (int y = 0; y < h; ++y) {
		for (int x = 0; x < w; ++x) {
			int r = 0, g = 0, b = 0;
			for (int sy = 0; sy < 2; ++sy)
				for (int sx = 0; sx < 2; ++sx) {
					double u = (x + 0.25 + 0.5 * sx) / w, v = (y + 0.25 + 0.5 * sy) / h;
					int part = stillShape(u, v, shift);
					Rgb8 c = part == 1 ? style.shirt : part == 2 ? style.skin : boardAt(u, v);
					r += c.r;
					g += c.g;
					b += c.b;
				}
			auto px = [&](int sum) { return uint8_t(std::clamp(sum / 4 + noise(rng), 0, 255)); };
			s.image.at(x, y) = { px(r), px(g), px(b) };
			s.truth.at(x, y) = stillShape((x + 0.5) / w, (y + 0.5) / h, shift) ? 255 : 0;
		}
	}
	// The band straddles the edge unevenly, as depth seeds do.
	int inner = band / 2 + int(seed % 3) - 1, outer = band - inner;
	Gray8Image eroded, dilated;
	MorphologyScratch scratch;
	erodeSquare(s.truth, std::max(1, inner), eroded, scratch);
	dilateSquare(s.truth, std::max(1, outer), dilated, scratch);
	s.trimap.resize(w, h);
	for (size_t i = 0; i < s.truth.size(); ++i)
		s.trimap.data()[i] = eroded.data()[i] ? kTrimapLecturer
				     : dilated.data()[i] ? kTrimapUndecided : kTrimapBoard;
	return s;
}

inline double intersectionOverUnion(const Gray8Image &mask, const Gray8Image &truth)
{
	size_t inter = 0, uni = 0;
	for (size_t i = 0; i < mask.size(); ++i) {
		bool a = mask.data()[i] >= 128, b = truth.data()[i] >= 128;
		inter += a && b;
		uni += a || b;
	}
	return uni ? double(inter) / uni : 1.0;
}

} // namespace depthkey::test
