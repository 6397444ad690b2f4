// How the board looks at each colour pixel (issue 11 section 3): one running
// colour per pixel, learned where the pixel is surely board and kept while
// the lecturer covers it. A band pixel that matches the board model at its
// own place is board: that tells white chalk on the board from a white shirt,
// and a dark vest from the dark board, where the two class signatures (one
// colour set for the whole board) cannot.
//
// Learning: every surely-board pixel of the trimap (outside the superset,
// the union of both depth frames' dilated areas), on one row in kRowStride
// per frame, the rows cycling, so the whole board is visited every
// kRowStride frames (160 ms at 25 fps) at a quarter of the cost. The mean
// moves by 1/2^rateShift of the difference per visit (ink written or wiped
// is 80 % followed within a second); a pixel seen for the first time takes the
// colour as it is.
//
// The room light changes (daylight, a lamp): behind a lecturer who stands
// still for a minute the model is as old as that, and a board 15 % darker
// than it was would no longer match. So the model is compared with the
// colour after a gain per channel, measured every frame on the rows learned
// (sum of the colour over sum of the model, Q8), which follows a global
// change of light at once.
// Memory: 4 bytes per pixel (RGB and a visit count). Pure, allocation-free
// after the first frame of a size.
#pragma once

#include <algorithm>

#include "algo/image.hpp"
#include "algo/kernel_path.hpp"
#include "algo/trimap.hpp"

#include <cstdint>
#include <cstdlib>
#include <vector>

namespace depthkey {

class BoardModel
{
public:
	static constexpr int kRowStride = 4;
	// teach() visits every 2nd row a frame, in turn (issue 28: at 1080p it
	// was 36 M instructions a frame on every row). Measured on the gate
	// (accuracy-table, seeds 1-3 / clean): every row 0.988/0.941,
	// 0.971/0.899, 0.967/0.904, 0.991/0.967; every 2nd 0.987/0.939,
	// 0.969/0.902, 0.967/0.904, 0.991/0.968; every 4th (learn()'s stride)
	// 0.983/0.938, 0.966/0.902, 0.968/0.902, 0.990/0.965.
	// Every 2nd row was on main for a day, measured at 640x480 only: at
	// 1920x1080 it took seed 1 from 0.974 to 0.962 (make accuracy-sizes'
	// floor 0.968; 7 December), so every row again until the cost is won
	// back elsewhere.
	static constexpr int kTeachRowStride = 1;
	static constexpr int kRateShift = 2;   // 1/4 of the difference per visit
	static constexpr uint8_t kLearnedVisits = 2; // visits before the model is trusted

	void reset();
	// trimap: the keyed trimap (colour size); its kTrimapBoard pixels are learned.
	void learn(const RgbImage &colour, const Gray8Image &trimap);
	// Inside the superset the board is learned where the frame's decision
	// was board with no lecturer pixel within marginPx in any of 8
	// directions (the board between his arm and body, or between his legs,
	// is never outside the superset while he stands there). The same rows
	// as the last learn(), within roi.
	void learnDecided(const RgbImage &colour, const Gray8Image &trimap, const Gray8Image &alpha, const Roi &roi,
			  int marginPx);

	// Taught a predicted board (algo/board_picture_prior.hpp): the picture
	// sampled under each pixel times gainQ8 per channel. Every pixel whose
	// mask is kTrimapBoard moves towards the prediction as a visit would, on
	// every kTeachRowStride-th row in turn; the light's gain then follows
	// the prediction on those rows.
	void teach(const RgbImage &sampled, const int gainQ8[3], const Gray8Image &mask);
	// Which row kernels teach(), learn() and learnDecided() run
	// (algo/kernel_path.hpp): the same bytes on each.
	void setKernelPath(KernelPath path) { kernelPath_ = path; }
	// c times a Q8 gain per channel, rounded, clamped at 255.
	static Rgb8 scaleQ8(Rgb8 c, const int gainQ8[3])
	{
		auto one = [](int v, int g) { return uint8_t(std::min(255, (v * g + 128) >> 8)); };
		return { one(c.r, gainQ8[0]), one(c.g, gainQ8[1]), one(c.b, gainQ8[2]) };
	}

	// The model of row y: RGB, and in .a the number of visits (saturating at
	// 255; 0 = never seen as board). Empty before the first learn().
	const Rgba8 *row(int y) const { return model_.row(y); }
	bool empty() const { return model_.empty(); }

	// The L1 distance of c to the model at (x, y), or -1 when the pixel has
	// not been learned well enough yet.
	int distance(int x, int y, Rgb8 c) const
	{
		const Rgba8 m = model_.row(y)[x];
		if (m.a < kLearnedVisits)
			return -1;
		return std::abs(int(c.r) - gained_[0][m.r]) + std::abs(int(c.g) - gained_[1][m.g]) +
		       std::abs(int(c.b) - gained_[2][m.b]);
	}
	// The light's gain per channel since the model was learned, Q8.
	const int *gainQ8() const { return gainQ8_; }

	// m += (c - m) / 4, rounded to nearest (an arithmetic shift of d + 2
	// floors; the mean settles within 2 levels of a steady colour, below
	// the sensor noise); a pixel never seen takes the colour as it is.
	// Inline: learn() calls it for a quarter of the board's pixels a frame.
	static void update(Rgba8 &m, Rgb8 c)
	{
		auto step = [](uint8_t mean, uint8_t value) {
			return uint8_t(mean + ((int(value) - int(mean) + (1 << (kRateShift - 1))) >> kRateShift));
		};
		if (m.a == 0)
			m = { c.r, c.g, c.b, 1 };
		else
			m = { step(m.r, c.r), step(m.g, c.g), step(m.b, c.b), uint8_t(std::min(255, m.a + 1)) };
	}

private:
	void setGains(const int gainQ8[3]);

	RgbaImage model_;
	KernelPath kernelPath_ = bestKernelPath();
	int phase_ = 0, lastPhase_ = 0;
	int teachPhase_ = 0; // the first row teach() visits next
	int gainQ8_[3] = { 256, 256, 256 };
	// (model * gainQ8 + 128) >> 8 per channel and model value (0..510),
	// tabulated when the gains change: distance() is called for every band
	// pixel, and three lookups replace three multiplies (issue 28).
	int16_t gained_[3][256];
	bool gainedFilled_ = false;
	// learnDecided()'s scratch rows: the alpha rows ORed (with a margin of
	// zeros each side) and which pixels are learned.
	std::vector<uint8_t> near_, select_;
};

} // namespace depthkey
