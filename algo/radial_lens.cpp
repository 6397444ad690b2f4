#include "algo/radial_lens.hpp"

#include <cmath>

namespace depthkey {

bool undistortRadius(double rd, double k1, double k2, double &r)
{
	r = rd;
	for (int i = 0; i < 20 && rd > 0; ++i) {
		const double r2 = r * r;
		const double f = r * (1.0 + r2 * (k1 + k2 * r2)) - rd;
		const double step = f / (1.0 + r2 * (3.0 * k1 + 5.0 * k2 * r2));
		r -= step;
		if (std::fabs(step) < 1e-15)
			break;
	}
	const double r2 = r * r;
	return std::isfinite(r) && r >= 0 && std::fabs(r * (1.0 + r2 * (k1 + k2 * r2)) - rd) < 1e-9 &&
	       1.0 + r2 * (3.0 * k1 + 5.0 * k2 * r2) > RadialLens::kMinSlope;
}

bool RadialLens::undistort(double x, double y, double &ix, double &iy) const
{
	const double dx = (x - cx) / f, dy = (y - cy) / f;
	const double rd = std::hypot(dx, dy);
	if (isPinhole() || rd == 0) {
		ix = x;
		iy = y;
		return true;
	}
	double r;
	if (!undistortRadius(rd, k1, k2, r))
		return false;
	ix = cx + f * dx * (r / rd);
	iy = cy + f * dy * (r / rd);
	return true;
}

} // namespace depthkey
