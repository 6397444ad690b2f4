#include "hal/sim/camera_rig.hpp"

#include "algo/radial_lens.hpp"

#include <Eigen/Geometry>
#include <cmath>

namespace depthkey {

namespace {

constexpr double kDegree = 3.14159265358979323846 / 180.0;

// Colour: a webcam with about 56 x 44 degrees field of view at 640x480 and
// mild barrel distortion. ToF: the SR-2's 160 x 124 sensor of 40 x 54 um
// pixels behind a wider lens (about 65 x 67 degrees) with stronger barrel
// distortion. The distortions are kept where the calibration's parallax
// model (cubic in position, 1/z parallax) fits them to a fraction of a pixel.
constexpr double kColourFocalAt640 = 600.0;
constexpr double kColourK1 = -0.03, kColourK2 = 0.005;
constexpr int kTofWidth = 160, kTofHeight = 124;
constexpr double kTofFx = 125.0;
constexpr double kTofPixelAspect = 40.0 / 54.0; // fy / fx
constexpr double kTofK1 = -0.09, kTofK2 = 0.008;
// Mounting: beside the colour camera (x), a little lower (y), turned by
// fractions of a degree as a hand-built bracket is.
constexpr double kMountDropM = 0.012;
constexpr double kYawDeg = -1.2, kPitchDeg = 0.6, kRollDeg = 0.4;

} // namespace

void LensModel::distort(double xn, double yn, double &x, double &y) const
{
	double r2 = xn * xn + yn * yn;
	double f = 1.0 + r2 * (k1 + k2 * r2);
	x = fx * xn * f + cx;
	y = fy * yn * f + cy;
}

void LensModel::undistort(double x, double y, double &xn, double &yn) const
{
	double xd = (x - cx) / fx, yd = (y - cy) / fy;
	double rd = std::sqrt(xd * xd + yd * yd);
	double r;
	undistortRadius(rd, k1, k2, r); // the simulator's lenses never fold within the image
	double scale = rd > 0 ? r / rd : 1.0;
	xn = xd * scale;
	yn = yd * scale;
}

bool LensModel::project(const Eigen::Vector3d &p, double &x, double &y) const
{
	if (p.z() <= 1e-6)
		return false;
	distort(p.x() / p.z(), p.y() / p.z(), x, y);
	return true;
}

void CameraRig::configure(int colourWidth, int colourHeight, bool distortion, int baselineMm)
{
	double scale = colourWidth / 640.0;
	colour_ = { colourWidth, colourHeight, kColourFocalAt640 * scale, kColourFocalAt640 * scale,
		    (colourWidth - 1) / 2.0, (colourHeight - 1) / 2.0,
		    distortion ? kColourK1 : 0.0, distortion ? kColourK2 : 0.0 };
	tof_ = { kTofWidth, kTofHeight, kTofFx, kTofFx * kTofPixelAspect,
		 (kTofWidth - 1) / 2.0, (kTofHeight - 1) / 2.0,
		 distortion ? kTofK1 : 0.0, distortion ? kTofK2 : 0.0 };
	rotation_ = (Eigen::AngleAxisd(kYawDeg * kDegree, Eigen::Vector3d::UnitY()) *
		     Eigen::AngleAxisd(kPitchDeg * kDegree, Eigen::Vector3d::UnitX()) *
		     Eigen::AngleAxisd(kRollDeg * kDegree, Eigen::Vector3d::UnitZ()))
			    .toRotationMatrix();
	origin_ = { baselineMm / 1000.0, kMountDropM, 0.0 };
}

Eigen::Vector3d CameraRig::toTof(const Eigen::Vector3d &pColour) const
{
	return rotation_.transpose() * (pColour - origin_);
}

Eigen::Vector3d CameraRig::toColour(const Eigen::Vector3d &pTof) const
{
	return rotation_ * pTof + origin_;
}

bool CameraRig::tofToColour(double u, double v, double zMetres, double &x, double &y) const
{
	double xn, yn;
	tof_.undistort(u, v, xn, yn);
	return colour_.project(toColour({ xn * zMetres, yn * zMetres, zMetres }), x, y);
}

bool CameraRig::colourToTof(double x, double y, double zMetres, double &u, double &v, double &tofZ) const
{
	double xn, yn;
	colour_.undistort(x, y, xn, yn);
	Eigen::Vector3d p = toTof({ xn * zMetres, yn * zMetres, zMetres });
	tofZ = p.z();
	return tof_.project(p, u, v);
}

} // namespace depthkey
