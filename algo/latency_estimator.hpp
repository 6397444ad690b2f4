// The depth camera's latency against the colour camera, measured from the
// two streams (pairing.offset_ms = "auto"): both see the lecturer move, so
// the motion in the colour images and in the depth images rises and falls
// together, the depth's shifted by the latency.
//   colour motion  per colour frame, the number of pixels on a sparse grid
//                  (every 8th row and column) whose luma changed by more
//                  than kColourStep since the last frame;
//   depth motion   per depth frame, the number of trusted pixels whose
//                  in-range state (near_mm..far_mm) flipped since the last;
// For each candidate offset L (-max_lag..+max_lag, 1 ms steps) the colour
// motion over each depth frame's interval, shifted by L, is read off the
// cumulative colour motion (linear between colour frames), and correlated
// (Pearson) with the depth motion; the best L, refined by a parabola through
// its neighbours, is the offset to add to depth timestamps (negative: depth
// frames are stamped after their capture).
// An estimate is valid once kMinDepthFrames of the last kDepthHistory depth
// frames are in, the motion varied, and the peak correlation is at least
// kMinCorrelation. The per-pixel work is integer; the correlation (a few
// hundred lags over at most 128 frames, once a second) is in double.
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
	static constexpr size_t kDepthHistory = 128;   // 12.8 s at 10 fps
	static constexpr size_t kMinDepthFrames = 30;
	static constexpr int kDepthBlock = 4;          // depth pixels per block side
	static constexpr double kMinCorrelation = 0.5;
	// The peak's own lobe, ms either side: about half a depth period.
	static constexpr int kPeakLobeMs = 50;

	void configure(int nearMm, int farMm, int maxLagMs = 300);
	void reset();

	void addColour(const RgbImage &rgb, uint64_t timestampNs);
	void addDepth(const DepthFrame &depth, uint64_t timestampNs);

	struct Estimate {
		bool valid = false;
		double offsetMs = 0;     // add to depth timestamps
		double correlation = 0;  // at the peak
		size_t depthFrames = 0;  // used
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
	// Cumulative colour motion at time t (ns), or false outside the history.
	bool colourMotionAt(double t, double &cumulative) const;
	double correlationAt(double lagNs, size_t &used) const;
	// The best correlation among the local maxima outside the peak's lobe
	// (-1 when there is none).
	static double rivalPeak(const std::vector<double> &r, size_t best);
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
	std::array<Sample, kDepthHistory> depth_{};
	size_t colourCount_ = 0, colourNext_ = 0, depthCount_ = 0, depthNext_ = 0;
	uint64_t colourTotal_ = 0;
};

} // namespace depthkey
