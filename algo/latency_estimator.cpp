#include "algo/latency_estimator.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace depthkey {

void LatencyEstimator::configure(int nearMm, int farMm, int maxLagMs)
{
	if (nearMm != nearMm_ || farMm != farMm_ || maxLagMs != maxLagMs_) {
		nearMm_ = nearMm;
		farMm_ = farMm;
		maxLagMs_ = maxLagMs;
		reset();
	}
}

void LatencyEstimator::reset()
{
	haveLuma_ = haveDepth_ = false;
	colourCount_ = colourNext_ = depthCount_ = depthNext_ = 0;
	colourTotal_ = 0;
}

void LatencyEstimator::addColour(const RgbImage &rgb, uint64_t timestampNs)
{
	const int gw = (rgb.width() + kGrid - 1) / kGrid, gh = (rgb.height() + kGrid - 1) / kGrid;
	if (gw != lumaWidth_ || gh != lumaHeight_) {
		lumaWidth_ = gw;
		lumaHeight_ = gh;
		luma_.assign(size_t(gw) * gh, 0); // once per size
		haveLuma_ = false;
	}
	uint32_t moved = 0;
	uint8_t *l = luma_.data();
	for (int y = 0; y < rgb.height(); y += kGrid) {
		const Rgb8 *row = rgb.row(y);
		for (int x = 0; x < rgb.width(); x += kGrid, ++l) {
			// Luma as (r + 2g + b) / 4: enough to see motion.
			const uint8_t v = uint8_t((row[x].r + 2 * row[x].g + row[x].b + 2) >> 2);
			moved += std::abs(int(v) - int(*l)) > kColourStep;
			*l = v;
		}
	}
	if (!haveLuma_) {
		haveLuma_ = true;
		moved = 0;
	}
	if (colourCount_ && timestampNs <= colour_[(colourNext_ + kColourHistory - 1) % kColourHistory].ns)
		return; // out of order: ignored
	colourTotal_ += moved;
	colour_[colourNext_] = { timestampNs, uint32_t(std::min<uint64_t>(colourTotal_, UINT32_MAX)) };
	colourNext_ = (colourNext_ + 1) % kColourHistory;
	colourCount_ = std::min(colourCount_ + 1, kColourHistory);
}

void LatencyEstimator::addDepth(const DepthFrame &depth, uint64_t timestampNs)
{
	const Gray16Image &mm = depth.depthMm;
	const int bw = mm.width() / kDepthBlock, bh = mm.height() / kDepthBlock;
	const size_t n = size_t(std::max(bw, 0)) * size_t(std::max(bh, 0));
	if (n != depthPixels_) {
		depthPixels_ = n;
		inRange_.assign(n, 0); // once per size
		blockCounts_.assign(size_t(std::max(bw, 0)), 0);
		haveDepth_ = false;
	}
	// Blocks of kDepthBlock^2 pixels, in range when most of their pixels
	// are: the ToF's noise flips single pixels at the range's edges every
	// frame, thousands of them, which would drown the lecturer's silhouette
	// moving. (No hysteresis: it would delay the flips, a bias in time.)
	const unsigned nearU = unsigned(nearMm_), span = unsigned(farMm_ - nearMm_);
	constexpr int kArea = kDepthBlock * kDepthBlock;
	uint32_t flipped = 0;
	for (int by = 0; by < bh; ++by) {
		std::fill(blockCounts_.begin(), blockCounts_.end(), uint16_t{ 0 });
		for (int y = by * kDepthBlock; y < (by + 1) * kDepthBlock; ++y) {
			const uint16_t *d = mm.row(y);
			for (int x = 0; x < bw * kDepthBlock; ++x)
				blockCounts_[size_t(x / kDepthBlock)] += unsigned(d[x]) - nearU <= span;
		}
		uint8_t *state = inRange_.data() + size_t(by) * size_t(bw);
		for (int bx = 0; bx < bw; ++bx) {
			const int count = blockCounts_[size_t(bx)];
			const uint8_t in = count * 2 > kArea;
			flipped += in != state[bx];
			state[bx] = in;
		}
	}
	if (!haveDepth_) {
		haveDepth_ = true;
		return; // no previous frame to compare with
	}
	if (depthCount_ && timestampNs <= depth_[(depthNext_ + kDepthHistory - 1) % kDepthHistory].ns)
		return;
	depth_[depthNext_] = { timestampNs, flipped };
	depthNext_ = (depthNext_ + 1) % kDepthHistory;
	depthCount_ = std::min(depthCount_ + 1, kDepthHistory);
}

bool LatencyEstimator::colourMotionAt(double t, double &cumulative) const
{
	if (colourCount_ < 2)
		return false;
	const size_t first = (colourNext_ + kColourHistory - colourCount_) % kColourHistory;
	auto at = [&](size_t k) -> const Sample & { return colour_[(first + k) % kColourHistory]; };
	if (t < double(at(0).ns) || t > double(at(colourCount_ - 1).ns))
		return false;
	// Binary search for the interval holding t.
	size_t lo = 0, hi = colourCount_ - 1;
	while (hi - lo > 1) {
		const size_t mid = (lo + hi) / 2;
		(double(at(mid).ns) <= t ? lo : hi) = mid;
	}
	const Sample &a = at(lo), &b = at(hi);
	const double f = b.ns > a.ns ? (t - double(a.ns)) / double(b.ns - a.ns) : 0.0;
	cumulative = double(a.motion) + f * (double(b.motion) - double(a.motion));
	return true;
}

double LatencyEstimator::correlationAt(double lagNs, size_t &used) const
{
	// Correlates the changes of the motion from one depth interval to the
	// next, not the motion itself: walking and standing make a slow swell
	// that correlates at any lag within a second, while the changes (he
	// starts, stops, turns) pin the lag down.
	double sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
	used = 0;
	size_t pairs = 0;
	const size_t first = (depthNext_ + kDepthHistory - depthCount_) % kDepthHistory;
	bool havePrevious = false;
	double previousX = 0, previousY = 0;
	for (size_t k = 1; k < depthCount_; ++k) {
		const Sample &prev = depth_[(first + k - 1) % kDepthHistory], &cur = depth_[(first + k) % kDepthHistory];
		double c0, c1;
		if (!colourMotionAt(double(prev.ns) + lagNs, c0) || !colourMotionAt(double(cur.ns) + lagNs, c1)) {
			havePrevious = false;
			continue;
		}
		// Per second, so that jittered intervals compare.
		const double seconds = std::max(1e-3, double(cur.ns - prev.ns) * 1e-9);
		const double x = (c1 - c0) / seconds, y = cur.motion / seconds;
		++used;
		if (havePrevious) {
			const double dx = x - previousX, dy = y - previousY;
			sx += dx;
			sy += dy;
			sxx += dx * dx;
			syy += dy * dy;
			sxy += dx * dy;
			++pairs;
		}
		previousX = x;
		previousY = y;
		havePrevious = true;
	}
	if (pairs < 3)
		return 0.0;
	const double n = double(pairs);
	const double vx = sxx - sx * sx / n, vy = syy - sy * sy / n;
	if (vx <= 0 || vy <= 0)
		return 0.0;
	return (sxy - sx * sy / n) / std::sqrt(vx * vy);
}

double LatencyEstimator::rivalPeak(const std::vector<double> &r, size_t best)
{
	// Local maxima only: the peak's own slope, just outside its lobe, is no
	// rival however high it is.
	double rival = -1.0;
	for (size_t k = 0; k < r.size(); ++k) {
		const size_t distance = k > best ? k - best : best - k;
		if (distance <= size_t(kPeakLobeMs))
			continue;
		const bool left = k == 0 || r[k - 1] <= r[k], right = k + 1 == r.size() || r[k + 1] <= r[k];
		if (left && right)
			rival = std::max(rival, r[k]);
	}
	return rival;
}

double LatencyEstimator::colourMotionPerSecond() const
{
	if (colourCount_ < 2 || lumaWidth_ <= 0 || lumaHeight_ <= 0)
		return 0.0;
	const size_t first = (colourNext_ + kColourHistory - colourCount_) % kColourHistory;
	const Sample &oldest = colour_[first], &newest = colour_[(first + colourCount_ - 1) % kColourHistory];
	const double seconds = double(newest.ns - oldest.ns) * 1e-9;
	const double cells = double(lumaWidth_) * double(lumaHeight_);
	return seconds > 0 ? double(newest.motion - oldest.motion) / cells / seconds : 0.0;
}

LatencyEstimator::Estimate LatencyEstimator::estimate() const
{
	Estimate e;
	if (depthCount_ < kMinDepthFrames)
		return e;
	// The same depth frames for every lag: those whose intervals shifted by
	// any lag lie within the colour history, so correlations compare.
	std::vector<double> r; // at most 2 * 1000 + 1 lags; estimate() is not per frame
	r.reserve(size_t(2 * maxLagMs_ + 1));
	size_t bestUsed = 0;
	int best = -1;
	for (int lag = -maxLagMs_; lag <= maxLagMs_; ++lag) {
		size_t used;
		r.push_back(correlationAt(lag * 1e6, used));
		if (best < 0 || r.back() > r[size_t(best)]) {
			best = int(r.size()) - 1;
			bestUsed = used;
		}
	}
	e.correlation = r[size_t(best)];
	e.depthFrames = bestUsed;
	double offset = best - maxLagMs_;
	if (best > 0 && best + 1 < int(r.size())) {
		const double a = r[size_t(best - 1)], b = r[size_t(best)], c = r[size_t(best + 1)];
		const double denominator = a - 2 * b + c;
		if (denominator < 0)
			offset += 0.5 * (a - c) / denominator;
	}
	e.offsetMs = offset;
	e.maxLagMs = maxLagMs_;
	e.peakMargin = e.correlation - rivalPeak(r, size_t(best));
	e.colourMotionPerS = colourMotionPerSecond();
	e.valid = bestUsed + 1 >= kMinDepthFrames && e.correlation >= kMinCorrelation;
	return e;
}

} // namespace depthkey
