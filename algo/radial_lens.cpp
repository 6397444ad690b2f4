#include "algo/radial_lens.hpp"

#include <cmath>

namespace depthkey {

bool RadialLens::undistort(double x, double y, double &ix, double &iy) const
{
	const double dx = (x - cx) / f, dy = (y - cy) / f;
	const double rd = std::hypot(dx, dy);
	if (isPinhole() || rd == 0) {
		ix = x;
		iy = y;
		return true;
	}
	// Newton on the radius: r (1 + k1 r^2 + k2 r^4) = rd, from r = rd.
	double r = rd;
	for (int i = 0; i < 20; ++i) {
		const double r2 = r * r;
		const double g = r * (1.0 + r2 * (k1 + k2 * r2)) - rd;
		const double slope = 1.0 + r2 * (3.0 * k1 + 5.0 * k2 * r2);
		if (!(slope > kMinSlope))
			return false; // past the fold of the radius
		const double step = g / slope;
		r -= step;
		if (std::fabs(step) < 1e-12)
			break;
	}
	const double r2 = r * r;
	if (!std::isfinite(r) || r < 0 || std::fabs(r * (1.0 + r2 * (k1 + k2 * r2)) - rd) > 1e-9)
		return false;
	ix = cx + f * dx * (r / rd);
	iy = cy + f * dy * (r / rd);
	return true;
}

} // namespace depthkey
