#include "tests/static_background_per_pixel_box.hpp"

#include <algorithm>
#include <climits>
#include <cstdint>
#include <cstdlib>
#include <cstring>

namespace depthkey::test {

void StaticBackgroundPerPixelBox::update(const Gray16Image &depthMm, Gray8Image &moving)
{
	const int w = depthMm.width(), h = depthMm.height();
	moving.resize(w, h);
	if (mean_.width() != w || mean_.height() != h) {
		mean_.resize(w, h);
		deviation_.resize(w, h);
		std::memset(mean_.data(), 0, mean_.size() * sizeof(uint16_t));
	}
	// In front of the background, 0 / 1, in a grid one pixel larger on
	// every side (0 there): the neighbour count below reads no bounds.
	const int stride = w + 2;
	if (inFront_.width() != stride || inFront_.height() != h + 2) {
		inFront_.resize(stride, h + 2);
		std::memset(inFront_.data(), 0, inFront_.size());
	}
	pooled_.resize(w, h);
	constexpr int kOne = 1 << kFractionBits;
	constexpr int kInvalid = INT32_MIN; // no depth: not in front of anything
	excess_.resize(size_t(w) * h);
	// How far each pixel lies in front of its mean, before this frame
	// updates the means (Q3 mm).
	for (int y = 0; y < h; ++y) {
		const uint16_t *d = depthMm.row(y);
		uint16_t *mean = mean_.row(y), *dev = deviation_.row(y);
		int32_t *e = excess_.data() + size_t(y) * w;
		for (int x = 0; x < w; ++x) {
			// Depths beyond 8191 mm (past the SR-2's range) are clamped so
			// that Q3 fits 16 bits; they are never in the lecturer's interval.
			const int z = (d[x] < 8191 ? d[x] : 8191) * kOne;
			if (z == 0) {
				e[x] = kInvalid;
				continue;
			}
			if (mean[x] == 0) {
				mean[x] = uint16_t(z);
				dev[x] = uint16_t(kToleranceMm * kOne);
			}
			e[x] = int32_t(mean[x]) - z;
		}
	}
	// A pixel's own depth against its mean misses an arm in the noisy
	// image edge (30 cm there: his 35 cm in front of the board is under the
	// threshold); the mean of its 3x3 box, with a third of the noise, sees
	// it. Before the update: every box sees this frame's deviations.
	for (int y = 0; y < h; ++y) {
		uint8_t *pooled = pooled_.row(y);
		const int32_t *e = excess_.data() + size_t(y) * w;
		for (int x = 0; x < w; ++x)
			pooled[x] = e[x] != kInvalid && inFrontPooled(x, y);
	}
	for (int y = 0; y < h; ++y) {
		uint16_t *mean = mean_.row(y), *dev = deviation_.row(y);
		const int32_t *e = excess_.data() + size_t(y) * w;
		const uint8_t *pooled = pooled_.row(y);
		uint8_t *m = inFront_.row(y + 1) + 1;
		for (int x = 0; x < w; ++x) {
			m[x] = 0;
			if (e[x] == kInvalid)
				continue;
			const int mu = mean[x], dv = dev[x];
			m[x] = e[x] > kToleranceMm * kOne + 2 * dv;
			if (m[x] || pooled[x]) {
				mean[x] = uint16_t(mu - kFadeMmPerFrame * kOne);
				continue;
			}
			const int z = mu - e[x]; // the clamped Q3 depth of the first pass
			// Arithmetic shifts of signed values (C++20): rounds towards
			// minus infinity, a bias of under 1/8 mm.
			mean[x] = uint16_t(mu + ((z - mu) >> kRateShift));
			dev[x] = uint16_t(dv + ((std::abs(z - mu) - dv) >> kRateShift));
		}
	}
	for (int y = 0; y < h; ++y) {
		const uint8_t *up = inFront_.row(y) + 1, *row = inFront_.row(y + 1) + 1, *down = inFront_.row(y + 2) + 1;
		const uint8_t *pooled = pooled_.row(y);
		uint8_t *out = moving.row(y);
		for (int x = 0; x < w; ++x) {
			const int neighbours = row[x - 1] + row[x + 1] + up[x] + down[x];
			out[x] = ((row[x] && neighbours >= 2) || pooled[x]) ? 255 : 0;
		}
	}
}

bool StaticBackgroundPerPixelBox::inFrontPooled(int x, int y) const
{
	// 512 / sqrt(n): the deviation of a mean of n pixels' noise.
	static constexpr int kInvSqrtQ9[10] = { 0, 512, 362, 296, 256, 229, 209, 194, 181, 171 };
	constexpr int kOne = 1 << kFractionBits;
	const int w = mean_.width(), h = mean_.height();
	int64_t sumExcess = 0, sumDeviation = 0;
	int n = 0;
	for (int yy = std::max(0, y - 1); yy <= std::min(h - 1, y + 1); ++yy) {
		const int32_t *e = excess_.data() + size_t(yy) * w;
		const uint16_t *dev = deviation_.row(yy);
		for (int xx = std::max(0, x - 1); xx <= std::min(w - 1, x + 1); ++xx) {
			if (e[xx] == INT32_MIN)
				continue;
			// A lone wild depth (a flying pixel) counts at most twice its
			// own threshold, so it cannot make its neighbours move.
			const int32_t cap = 2 * (kToleranceMm * kOne + 2 * dev[xx]);
			sumExcess += std::clamp(e[xx], -cap, cap);
			sumDeviation += dev[xx];
			n++;
		}
	}
	if (n < 4)
		return false;
	return sumExcess > int64_t(n) * kToleranceMm * kOne + ((2 * sumDeviation * kInvSqrtQ9[n]) >> 9);
}

} // namespace depthkey::test
