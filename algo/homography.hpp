// A plane-to-plane projective map (3x3, row-major, h[8] normalised to 1):
// here the colour camera's view of the board's display -> the board's own
// pixels. Pixel coordinates have pixel i's centre at i, as everywhere.
#pragma once

#include <array>
#include <cmath>

namespace depthkey {

struct Homography {
	std::array<double, 9> h{ 1, 0, 0, 0, 1, 0, 0, 0, 1 };

	// False when the point maps to infinity (behind the horizon).
	bool apply(double x, double y, double &u, double &v) const
	{
		double w = h[6] * x + h[7] * y + h[8];
		if (!(std::fabs(w) > 1e-12))
			return false;
		u = (h[0] * x + h[1] * y + h[2]) / w;
		v = (h[3] * x + h[4] * y + h[5]) / w;
		return true;
	}
	double determinant() const
	{
		return h[0] * (h[4] * h[8] - h[5] * h[7]) - h[1] * (h[3] * h[8] - h[5] * h[6]) +
		       h[2] * (h[3] * h[7] - h[4] * h[6]);
	}
	// The inverse map; false when singular.
	bool inverse(Homography &out) const;
	// this then next: x -> next(this(x)).
	Homography then(const Homography &next) const;
	bool operator==(const Homography &) const = default;
};

// Board pixels of a picture srcW x srcH -> pixels of the same board shown at
// dstW x dstH (pixel centres kept: u' = (u + 0.5) * dstW / srcW - 0.5).
Homography boardScaling(int srcWidth, int srcHeight, int dstWidth, int dstHeight);

} // namespace depthkey
