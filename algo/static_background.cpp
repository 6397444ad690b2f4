#include "algo/static_background.hpp"

#include <cstdlib>
#include <cstring>

namespace depthkey {

void StaticBackground::update(const Gray16Image &depthMm, Gray8Image &moving)
{
	const int w = depthMm.width(), h = depthMm.height();
	const size_t n = static_cast<size_t>(w) * h;
	moving.resize(w, h);
	if (mean_.width() != w || mean_.height() != h) {
		mean_.resize(w, h);
		deviation_.resize(w, h);
		std::memset(mean_.data(), 0, n * sizeof(uint16_t));
	}
	constexpr int kOne = 1 << kFractionBits;
	const uint16_t *d = depthMm.data();
	uint16_t *mean = mean_.data(), *dev = deviation_.data();
	inFront_.resize(w, h);
	uint8_t *m = inFront_.data();
	for (size_t i = 0; i < n; ++i) {
		// Depths beyond 8191 mm (past the SR-2's range) are clamped so that
		// Q3 fits 16 bits; they are never in the lecturer's interval.
		const int z = (d[i] < 8191 ? d[i] : 8191) * kOne;
		if (z == 0) {
			m[i] = 0;
			continue;
		}
		if (mean[i] == 0) {
			mean[i] = uint16_t(z);
			dev[i] = uint16_t(kToleranceMm * kOne);
		}
		const int mu = mean[i], dv = dev[i];
		const bool isMoving = mu - z > kToleranceMm * kOne + 2 * dv;
		m[i] = isMoving ? 255 : 0;
		if (isMoving) {
			mean[i] = uint16_t(mu - kFadeMmPerFrame * kOne);
			continue;
		}
		// Arithmetic shifts of signed values (C++20): rounds towards
		// minus infinity, a bias of under 1/8 mm.
		mean[i] = uint16_t(mu + ((z - mu) >> kRateShift));
		dev[i] = uint16_t(dv + ((std::abs(z - mu) - dv) >> kRateShift));
	}
	for (int y = 0; y < h; ++y) {
		const uint8_t *up = y > 0 ? inFront_.row(y - 1) : nullptr, *row = inFront_.row(y);
		const uint8_t *down = y + 1 < h ? inFront_.row(y + 1) : nullptr;
		uint8_t *out = moving.row(y);
		for (int x = 0; x < w; ++x) {
			int neighbours = (x > 0 && row[x - 1]) + (x + 1 < w && row[x + 1]) + (up && up[x]) + (down && down[x]);
			out[x] = row[x] && neighbours >= 2 ? 255 : 0;
		}
	}
}

} // namespace depthkey
