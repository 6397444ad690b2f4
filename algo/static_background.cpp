#include "algo/static_background.hpp"

#include <algorithm>
#include <climits>
#include <cstdint>
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
	poolBoxes(w, h);
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

void StaticBackground::poolBoxes(int w, int h)
{
	// Each pixel's share of its boxes (capped excess, deviation, 1 when
	// measured), summed along rows over x-1..x+1 (the image border simply
	// ends a box), then the three rows' sums added: every box costs a few
	// additions instead of nine clamps. Sums of at most nine values under
	// 2^19 fit int32, as do the products below (exact, as per box).
	constexpr int kOne = 1 << kFractionBits;
	rowExcess_.resize(size_t(w) * h);
	rowDeviation_.resize(size_t(w) * h);
	rowCount_.resize(size_t(w) * h);
	for (int y = 0; y < h; ++y) {
		const int32_t *e = excess_.data() + size_t(y) * w;
		const uint16_t *dev = deviation_.row(y);
		int32_t *se = rowExcess_.data() + size_t(y) * w, *sd = rowDeviation_.data() + size_t(y) * w;
		uint8_t *sn = rowCount_.data() + size_t(y) * w;
		// The pixel's own share, into the row sums' places first.
		for (int x = 0; x < w; ++x) {
			const bool valid = e[x] != INT32_MIN;
			// A lone wild depth (a flying pixel) counts at most twice its
			// own threshold, so it cannot make its neighbours move.
			const int32_t cap = 2 * (kToleranceMm * kOne + 2 * dev[x]);
			se[x] = valid ? std::clamp(e[x], -cap, cap) : 0;
			sd[x] = valid ? dev[x] : 0;
			sn[x] = valid;
		}
		int32_t pe = 0, pd = 0;
		int pn = 0;
		for (int x = 0; x < w; ++x) {
			const int32_t ce = se[x], cd = sd[x];
			const int cn = sn[x];
			const bool last = x + 1 == w;
			se[x] = pe + ce + (last ? 0 : se[x + 1]);
			sd[x] = pd + cd + (last ? 0 : sd[x + 1]);
			sn[x] = uint8_t(pn + cn + (last ? 0 : sn[x + 1]));
			pe = ce, pd = cd, pn = cn;
		}
	}
	// 512 / sqrt(n): the deviation of a mean of n pixels' noise.
	static constexpr int kInvSqrtQ9[10] = { 0, 512, 362, 296, 256, 229, 209, 194, 181, 171 };
	for (int y = 0; y < h; ++y) {
		const size_t up = size_t(y > 0 ? y - 1 : y) * w, row = size_t(y) * w, down = size_t(y + 1 < h ? y + 1 : y) * w;
		const bool haveUp = y > 0, haveDown = y + 1 < h;
		const int32_t *e = excess_.data() + row;
		uint8_t *pooled = pooled_.row(y);
		for (int x = 0; x < w; ++x) {
			const int32_t sumExcess = rowExcess_[row + x] + (haveUp ? rowExcess_[up + x] : 0) +
						 (haveDown ? rowExcess_[down + x] : 0);
			const int32_t sumDeviation = rowDeviation_[row + x] + (haveUp ? rowDeviation_[up + x] : 0) +
						    (haveDown ? rowDeviation_[down + x] : 0);
			const int n = rowCount_[row + x] + (haveUp ? rowCount_[up + x] : 0) + (haveDown ? rowCount_[down + x] : 0);
			pooled[x] = e[x] != INT32_MIN && n >= 4 &&
				    sumExcess > n * kToleranceMm * kOne + ((2 * sumDeviation * kInvSqrtQ9[n]) >> 9);
		}
	}
}

} // namespace depthkey
