// How far a fitted mapping lands from where a point really is, in colour
// pixels: the figures the calibration reports per model, depth and set.
#pragma once

#include <algorithm>
#include <cmath>

namespace depthkey {

struct ResidualStats {
	int points = 0;
	double rmsPx = 0;       // root mean square of the Euclidean distance
	double maxPx = 0;       // the largest distance
};

class ResidualAccumulator
{
public:
	void add(double dxPx, double dyPx)
	{
		double squared = dxPx * dxPx + dyPx * dyPx;
		sumSquares_ += squared;
		maxSquared_ = std::max(maxSquared_, squared);
		points_++;
	}

	ResidualStats stats() const
	{
		if (points_ == 0)
			return {};
		return { points_, std::sqrt(sumSquares_ / points_), std::sqrt(maxSquared_) };
	}

private:
	double sumSquares_ = 0;
	double maxSquared_ = 0;
	int points_ = 0;
};

} // namespace depthkey
