#include "algo/latency_estimator.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace depthkey {

void LatencyEstimator::configure(int nearMm, int farMm, int maxLagMs)
{
	if (nearMm != nearMm_ || farMm != farMm_ || maxLagMs != maxLagMs_ || lags_.empty()) {
		nearMm_ = nearMm;
		farMm_ = farMm;
		maxLagMs_ = maxLagMs;
		// Once per configuration: 2 * max_lag + 1 lags.
		lags_.assign(size_t(2 * maxLagMs_ + 1), LagSums{});
		cumulative_.assign(lags_.size(), 0.0);
		sharp_.assign(lags_.size(), 0);
		r_.assign(lags_.size(), 0.0);
		reset();
	}
}

void LatencyEstimator::reset()
{
	haveLuma_ = haveDepth_ = false;
	colourCount_ = colourNext_ = pendingCount_ = pendingNext_ = 0;
	colourTotal_ = newestDepthNs_ = 0;
	std::fill(lags_.begin(), lags_.end(), LagSums{});
	intervals_ = 0;
	colourPeriodNs_ = 0;
	chain_ = 0;
	lastFoldedNs_ = 0;
	lastY_ = 0;
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
	if (colourCount_) {
		// The usual colour interval, a slow average (a gap of a second is
		// a camera gone, not its rate).
		const double interval = double(timestampNs - colour_[(colourNext_ + kColourHistory - 1) % kColourHistory].ns);
		if (interval < 1e9)
			colourPeriodNs_ = colourPeriodNs_ > 0 ? colourPeriodNs_ + (interval - colourPeriodNs_) / 32 : interval;
	}
	colourTotal_ += moved;
	colour_[colourNext_] = { timestampNs, uint32_t(std::min<uint64_t>(colourTotal_, UINT32_MAX)) };
	colourNext_ = (colourNext_ + 1) % kColourHistory;
	colourCount_ = std::min(colourCount_ + 1, kColourHistory);
	foldPending();
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
	if (timestampNs <= newestDepthNs_)
		return; // out of order: ignored
	newestDepthNs_ = timestampNs;
	if (pendingCount_ == kPendingDepth) {
		// No colour for seconds: the oldest waiting frame is dropped, and
		// with it the chain of consecutive intervals.
		--pendingCount_;
		chain_ = 0;
	}
	pending_[pendingNext_] = { timestampNs, flipped };
	pendingNext_ = (pendingNext_ + 1) % kPendingDepth;
	++pendingCount_;
	foldPending();
}

bool LatencyEstimator::colourMotionAlong(double t0, double stepNs)
{
	const size_t n = cumulative_.size();
	// A point in a gap of more than kMaxGapPeriods usual colour intervals
	// is not sharp: the motion is spread evenly over the gap, which it was
	// not. (On a busy box the loop stalls, and the colour and depth frames
	// after a stall come together: lags near 0 would read sharp colour at
	// both ends of such intervals while the true lag reads the gap, a pull
	// of 20-30 ms towards 0.)
	const double maxGapNs = kMaxGapPeriods * colourPeriodNs_;
	if (colourCount_ < 2 || t0 < double(colourAt(0).ns) ||
	    t0 + double(n - 1) * stepNs > double(colourAt(colourCount_ - 1).ns))
		return false;
	// The first interval by binary search, then forward with the lags.
	size_t lo = 0, hi = colourCount_ - 1;
	while (hi - lo > 1) {
		const size_t mid = (lo + hi) / 2;
		(double(colourAt(mid).ns) <= t0 ? lo : hi) = mid;
	}
	for (size_t k = 0; k < n; ++k) {
		const double t = t0 + double(k) * stepNs;
		while (lo + 2 < colourCount_ && double(colourAt(lo + 1).ns) <= t)
			++lo;
		const Sample &a = colourAt(lo), &b = colourAt(lo + 1);
		const double f = b.ns > a.ns ? std::clamp((t - double(a.ns)) / double(b.ns - a.ns), 0.0, 1.0) : 0.0;
		cumulative_[k] = double(a.motion) + f * (double(b.motion) - double(a.motion));
		sharp_[k] = double(b.ns - a.ns) <= maxGapNs;
	}
	return true;
}

void LatencyEstimator::foldPending()
{
	if (lags_.empty() || colourCount_ < 2)
		return;
	const uint64_t newestColourNs = colourAt(colourCount_ - 1).ns;
	const uint64_t lagNs = uint64_t(maxLagMs_) * 1'000'000;
	while (pendingCount_) {
		const Sample &depth = pending_[(pendingNext_ + kPendingDepth - pendingCount_) % kPendingDepth];
		if (depth.ns + lagNs > newestColourNs)
			return; // its colour is still to come
		fold(depth);
		--pendingCount_;
	}
}

void LatencyEstimator::fold(const Sample &depth)
{
	// The cumulative colour motion at the depth frame's time shifted by
	// each lag; before the colour history (the first frames) the chain
	// starts afresh.
	if (!colourMotionAlong(double(depth.ns) - maxLagMs_ * 1e6, 1e6)) {
		chain_ = 0;
		return;
	}
	const bool haveInterval = chain_ >= 1, haveChange = chain_ == 2;
	// Per second, so that jittered intervals compare. The changes of the
	// motion from one interval to the next are correlated, not the motion
	// itself: walking and standing make a slow swell that correlates at any
	// lag within a second, while the changes (he starts, stops, turns) pin
	// the lag down.
	const double seconds = std::max(1e-3, double(depth.ns - lastFoldedNs_) * 1e-9);
	const double y = depth.motion / seconds, dy = y - lastY_;
	// Older evidence fades with the time passed, so a changed latency
	// takes over.
	const double decay = haveInterval ? std::exp2(-seconds / kHalfLifeS) : 1.0;
	if (haveInterval)
		intervals_ = intervals_ * decay + 1.0;
	for (size_t k = 0; k < lags_.size(); ++k) {
		LagSums &s = lags_[k];
		// Each lag keeps its own chain: an interval counts where the
		// colour at both its ends is sharp, a change where two
		// consecutive intervals do.
		const bool xSharp = haveInterval && s.lastSharp && sharp_[k];
		const double x = xSharp ? (cumulative_[k] - s.lastCumulative) / seconds : 0.0;
		s.w *= decay;
		s.sx *= decay;
		s.sy *= decay;
		s.sxx *= decay;
		s.syy *= decay;
		s.sxy *= decay;
		if (haveChange && xSharp && s.lastXSharp) {
			const double dx = x - s.lastX;
			s.w += 1.0;
			s.sx += dx;
			s.sy += dy;
			s.sxx += dx * dx;
			s.syy += dy * dy;
			s.sxy += dx * dy;
		}
		s.lastX = x;
		s.lastXSharp = xSharp;
		s.lastCumulative = cumulative_[k];
		s.lastSharp = sharp_[k];
	}
	lastY_ = y;
	lastFoldedNs_ = depth.ns;
	chain_ = haveInterval ? 2 : 1;
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

double LatencyEstimator::peakShift(const std::vector<double> &r, size_t best)
{
	// A parabola fitted (least squares) to the curve within kFitHalfWidthMs
	// of the best lag, as far as the curve reaches on both sides: the top of
	// the peak is flat and bumpy (a few intervals more or less move its
	// highest point by 10 ms from one second to the next), its shape is not.
	const size_t w = std::min({ size_t(kFitHalfWidthMs), best, r.size() - 1 - best });
	if (w == 0)
		return 0.0;
	double s0 = 0, s2 = 0, s4 = 0, sr = 0, srd = 0, srd2 = 0;
	for (size_t k = best - w; k <= best + w; ++k) {
		const double d = double(k) - double(best), d2 = d * d;
		s0 += 1;
		s2 += d2;
		s4 += d2 * d2;
		sr += r[k];
		srd += r[k] * d;
		srd2 += r[k] * d2;
	}
	// Symmetric d: the slope alone from sum(r d), the curvature from the
	// 2x2 system of the constant and the square.
	const double slope = srd / s2;
	const double curvature = (s0 * srd2 - s2 * sr) / (s0 * s4 - s2 * s2);
	if (curvature >= 0)
		return 0.0;
	return std::clamp(-slope / (2 * curvature), -double(w), double(w));
}

double LatencyEstimator::colourMotionPerSecond() const
{
	if (colourCount_ < 2 || lumaWidth_ <= 0 || lumaHeight_ <= 0)
		return 0.0;
	const Sample &oldest = colourAt(0), &newest = colourAt(colourCount_ - 1);
	const double seconds = double(newest.ns - oldest.ns) * 1e-9;
	const double cells = double(lumaWidth_) * double(lumaHeight_);
	return seconds > 0 ? double(newest.motion - oldest.motion) / cells / seconds : 0.0;
}

LatencyEstimator::Estimate LatencyEstimator::estimate() const
{
	Estimate e;
	e.depthFrames = size_t(std::lround(intervals_));
	e.colourMotionPerS = colourMotionPerSecond();
	e.maxLagMs = maxLagMs_;
	if (e.depthFrames < kMinDepthFrames)
		return e;
	size_t best = 0;
	for (size_t k = 0; k < lags_.size(); ++k) {
		const LagSums &s = lags_[k];
		const double vx = s.sxx - s.sx * s.sx / s.w, vy = s.syy - s.sy * s.sy / s.w;
		r_[k] = s.w >= 3.0 && vx > 0 && vy > 0 ? (s.sxy - s.sx * s.sy / s.w) / std::sqrt(vx * vy) : 0.0;
		if (r_[k] > r_[best])
			best = k;
	}
	// What the best lag rests on: the changes it summed, decayed.
	e.depthFrames = size_t(std::lround(lags_[best].w));
	if (e.depthFrames < kMinDepthFrames)
		return e;
	e.correlation = r_[best];
	e.offsetMs = double(best) - maxLagMs_ + peakShift(r_, best);
	e.peakMargin = e.correlation - rivalPeak(r_, best);
	e.valid = e.correlation >= kMinCorrelation;
	return e;
}

} // namespace depthkey
