// The depth camera's latency against the colour camera, measured from the
// two streams (pairing.offset_ms = "auto"): both see the lecturer move, so
// the motion in the colour images and in the depth images rises and falls
// together, the depth's shifted by the latency.
//   colour motion  per colour frame, the number of pixels on a sparse grid
//                  (every 8th row and column) whose luma changed by more
//                  than kColourStep since the last frame;
//   depth motion   per depth frame, the number of 4x4 blocks whose in-range
//                  majority (near_mm..far_mm) flipped since the last.
// For each candidate offset L (-max_lag..+max_lag, 1 ms steps) the colour
// motion over each depth frame's interval, shifted by L, is read off the
// cumulative colour motion (linear between colour frames), and correlated
// (Pearson) with the depth motion; the best L, refined by a parabola fitted
// to the peak's top, is the offset to add to depth timestamps (negative: depth
// frames are stamped after their capture).
// The evidence accumulates (issue 29 §3): each depth interval is folded into
// per-lag correlation sums once the colour around it (+-max_lag) has come,
// and the sums decay with a half-life of kHalfLifeS, so the estimate
// converges on all the motion seen since start, not on what the lecturer did
// in the last few seconds, and still finds an offset that changed. Folding
// one interval costs a walk over the lags (no recompute of a window); an
// estimate reads the sums. The per-pixel work is integer, the sums double.
// Pure: times come in as the frames' timestamps.
#pragma once

#include "algo/frames.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace depthkey {

class LatencyEstimator
{
public:
	static constexpr int kGrid = 8;                // colour grid step, pixels
	static constexpr int kColourStep = 12;         // luma change that counts (4x the sensor noise)
	static constexpr size_t kColourHistory = 512;  // 20 s at 25 fps
	// Depth frames waiting for the colour up to max_lag after them: 3.2 s
	// at 10 fps (colour that late is a camera gone, and the chain restarts).
	static constexpr size_t kPendingDepth = 32;
	static constexpr size_t kMinDepthFrames = 30;
	static constexpr int kDepthBlock = 4;          // depth pixels per block side
	static constexpr double kMinCorrelation = 0.5;
	// The peak's own lobe, ms either side: about half a depth period.
	static constexpr int kPeakLobeMs = 50;
	// The peak's top, ms either side of the best lag, that the sub-lag
	// refinement fits.
	static constexpr int kFitHalfWidthMs = 25;
	// The evidence's half-life: long enough that the estimate rests on
	// minutes of lecture, short enough that a changed latency (another hub,
	// a firmware update) takes over within a few minutes.
	static constexpr double kHalfLifeS = 90.0;
	// Colour gaps longer than this many usual colour intervals leave the
	// lags whose points fall in them out of an interval (see fold()).
	static constexpr double kMaxGapPeriods = 2.5;

	void configure(int nearMm, int farMm, int maxLagMs = 300);
	void reset();

	void addColour(const RgbImage &rgb, uint64_t timestampNs);
	void addDepth(const DepthFrame &depth, uint64_t timestampNs);

	struct Estimate {
		bool valid = false;
		double offsetMs = 0;     // add to depth timestamps
		double correlation = 0;  // at the peak
		// Depth intervals in the best lag's evidence, decayed (at 10 fps
		// at most 10 x kHalfLifeS / ln 2).
		size_t depthFrames = 0;
		// How clearly the peak beats the rest: the peak's correlation less
		// the best correlation of any other local maximum further than
		// kPeakLobeMs away (1 = no rival; small = an ambiguous lag).
		double peakMargin = 0;
		// Colour motion: the share of the grid whose luma changed, per
		// second, over the colour history (too little: nothing to time;
		// the depth's in-range flips are not used, its noise flips too).
		double colourMotionPerS = 0;
		int maxLagMs = 0;        // the search window, +-
	};
	Estimate estimate() const;

private:
	struct Sample {
		uint64_t ns;
		uint32_t motion;
	};
	// Per lag: the correlation sums of the changes (decayed), and the
	// chain's last cumulative colour motion and last colour rate.
	struct LagSums {
		double w = 0, sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
		double lastCumulative = 0, lastX = 0;
		bool lastSharp = false, lastXSharp = false;
	};
	const Sample &colourAt(size_t k) const
	{
		return colour_[(colourNext_ + kColourHistory - colourCount_ + k) % kColourHistory];
	}
	// Cumulative colour motion at t0 + k * stepNs for each lag k into
	// cumulative_, walking the colour history once; false when any of those
	// times lies outside it.
	bool colourMotionAlong(double t0, double stepNs);
	// Folds the pending depth frames whose colour has come.
	void foldPending();
	void fold(const Sample &depth);
	// The best correlation among the local maxima outside the peak's lobe
	// (-1 when there is none).
	static double rivalPeak(const std::vector<double> &r, size_t best);
	// The refinement of the best lag, ms, from the shape of the peak.
	static double peakShift(const std::vector<double> &r, size_t best);
	double colourMotionPerSecond() const;

	int nearMm_ = 500, farMm_ = 1850, maxLagMs_ = 300;
	std::vector<uint8_t> luma_;              // the last colour frame's grid
	std::vector<uint8_t> inRange_;           // the last depth frame's in-range blocks
	std::vector<uint16_t> blockCounts_;      // in-range pixels per block of a block row
	int lumaWidth_ = 0, lumaHeight_ = 0;
	size_t depthPixels_ = 0;
	bool haveLuma_ = false, haveDepth_ = false;
	// Ring buffers; colour holds cumulative motion.
	std::array<Sample, kColourHistory> colour_{};
	std::array<Sample, kPendingDepth> pending_{};
	size_t colourCount_ = 0, colourNext_ = 0, pendingCount_ = 0, pendingNext_ = 0;
	uint64_t colourTotal_ = 0, newestDepthNs_ = 0;
	// The accumulated evidence, one entry per lag (allocated at configure).
	std::vector<LagSums> lags_;
	std::vector<double> cumulative_;         // scratch of colourMotionAlong
	std::vector<uint8_t> sharp_;             // its points outside long colour gaps
	double colourPeriodNs_ = 0;              // the usual colour interval (average)
	mutable std::vector<double> r_;          // scratch of estimate()
	double intervals_ = 0;                   // decayed count of intervals folded
	// The chain of folded intervals: 0 none, 1 a cumulative per lag, 2 also
	// a rate (the next interval adds a change).
	int chain_ = 0;
	uint64_t lastFoldedNs_ = 0;
	double lastY_ = 0;
};

} // namespace depthkey
