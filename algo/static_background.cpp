#include "algo/static_background.hpp"

#include <cstdlib>
#include <cstring>

namespace depthkey {

void StaticBackground::update(const Gray16Image &depthMm, Gray8Image &moving)
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
	constexpr int kOne = 1 << kFractionBits;
	for (int y = 0; y < h; ++y) {
		const uint16_t *d = depthMm.row(y);
		uint16_t *mean = mean_.row(y), *dev = deviation_.row(y);
		uint8_t *m = inFront_.row(y + 1) + 1;
		for (int x = 0; x < w; ++x) {
			// Depths beyond 8191 mm (past the SR-2's range) are clamped so
			// that Q3 fits 16 bits; they are never in the lecturer's interval.
			const int z = (d[x] < 8191 ? d[x] : 8191) * kOne;
			if (z == 0) {
				m[x] = 0;
				continue;
			}
			if (mean[x] == 0) {
				mean[x] = uint16_t(z);
				dev[x] = uint16_t(kToleranceMm * kOne);
			}
			const int mu = mean[x], dv = dev[x];
			const bool isMoving = mu - z > kToleranceMm * kOne + 2 * dv;
			m[x] = isMoving;
			if (isMoving) {
				mean[x] = uint16_t(mu - kFadeMmPerFrame * kOne);
				continue;
			}
			// Arithmetic shifts of signed values (C++20): rounds towards
			// minus infinity, a bias of under 1/8 mm.
			mean[x] = uint16_t(mu + ((z - mu) >> kRateShift));
			dev[x] = uint16_t(dv + ((std::abs(z - mu) - dv) >> kRateShift));
		}
	}
	for (int y = 0; y < h; ++y) {
		const uint8_t *up = inFront_.row(y) + 1, *row = inFront_.row(y + 1) + 1, *down = inFront_.row(y + 2) + 1;
		uint8_t *out = moving.row(y);
		for (int x = 0; x < w; ++x) {
			const int neighbours = row[x - 1] + row[x + 1] + up[x] + down[x];
			out[x] = (row[x] && neighbours >= 2) ? 255 : 0;
		}
	}
}

} // namespace depthkey
