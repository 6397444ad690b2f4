#include "algo/homography.hpp"

namespace depthkey {

bool Homography::inverse(Homography &out) const
{
	double det = determinant();
	if (!(std::fabs(det) > 1e-15) || !std::isfinite(det))
		return false;
	const auto &m = h;
	std::array<double, 9> a{ m[4] * m[8] - m[5] * m[7], m[2] * m[7] - m[1] * m[8], m[1] * m[5] - m[2] * m[4],
				 m[5] * m[6] - m[3] * m[8], m[0] * m[8] - m[2] * m[6], m[2] * m[3] - m[0] * m[5],
				 m[3] * m[7] - m[4] * m[6], m[1] * m[6] - m[0] * m[7], m[0] * m[4] - m[1] * m[3] };
	// The adjugate is the inverse up to scale; normalise so h[8] = 1 when possible.
	double s = std::fabs(a[8]) > 1e-12 ? 1.0 / a[8] : 1.0 / det;
	for (int i = 0; i < 9; ++i)
		out.h[i] = a[i] * s;
	return true;
}

Homography Homography::then(const Homography &next) const
{
	Homography out;
	for (int r = 0; r < 3; ++r)
		for (int c = 0; c < 3; ++c) {
			double sum = 0;
			for (int k = 0; k < 3; ++k)
				sum += next.h[r * 3 + k] * h[k * 3 + c];
			out.h[r * 3 + c] = sum;
		}
	if (double w = out.h[8]; std::fabs(w) > 1e-12)
		for (double &v : out.h)
			v /= w;
	return out;
}

Homography boardScaling(int srcWidth, int srcHeight, int dstWidth, int dstHeight)
{
	double sx = double(dstWidth) / srcWidth, sy = double(dstHeight) / srcHeight;
	Homography s;
	s.h = { sx, 0, 0.5 * sx - 0.5, 0, sy, 0.5 * sy - 0.5, 0, 0, 1 };
	return s;
}

} // namespace depthkey
