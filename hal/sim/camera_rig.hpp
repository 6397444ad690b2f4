// The simulated camera pair: a colour camera and a time-of-flight camera
// mounted beside it, each with its own lens. All scene geometry lives in the
// colour camera's frame (x right, y down, z forward, metres).
//
// Pixel coordinates are continuous with pixel i's centre at i (so the image
// spans [-0.5, width - 0.5]), as algo/mapping_model.hpp assumes.
//
// The ToF's depth value is z along its own optical axis (what a Z16 camera
// delivers), not the radial distance; tofToColour() is the exact ground truth
// of the depth -> colour mapping that calibration must recover.
#pragma once

#include <Eigen/Core>

namespace depthkey {

// A pinhole with two-term radial distortion (Brown): a normalised point
// (xn, yn) is seen at  fx * xn * (1 + k1 r^2 + k2 r^4) + cx  (y likewise).
struct LensModel {
	int width = 0, height = 0;
	double fx = 0, fy = 0;   // fx != fy: non-square pixels (the SR-2's are 40 x 54 um)
	double cx = 0, cy = 0;
	double k1 = 0, k2 = 0;

	void distort(double xn, double yn, double &x, double &y) const;
	// Inverse of distort() (fixed-point iteration, converges for moderate k).
	void undistort(double x, double y, double &xn, double &yn) const;
	// Projects a point in this camera's frame; false if behind the camera.
	bool project(const Eigen::Vector3d &p, double &x, double &y) const;
};

class CameraRig
{
public:
	// The default rig for a colour image of the given size; distortion false
	// makes both lenses ideal pinholes; baselineMm is the ToF's offset.
	void configure(int colourWidth, int colourHeight, bool distortion, int baselineMm);

	const LensModel &colour() const { return colour_; }
	const LensModel &tof() const { return tof_; }

	// ToF camera pose in the colour frame: p_colour = rotation * p_tof + origin.
	const Eigen::Matrix3d &tofRotation() const { return rotation_; }
	const Eigen::Vector3d &tofOrigin() const { return origin_; }

	// Ground truth: ToF pixel (u, v) seeing depth zMetres lands at colour
	// pixel (x, y). False if the point is behind the colour camera.
	bool tofToColour(double u, double v, double zMetres, double &x, double &y) const;
	// The inverse view: colour pixel (x, y) seeing a point at colour-frame
	// depth zMetres lands at ToF pixel (u, v) with ToF depth tofZ.
	bool colourToTof(double x, double y, double zMetres, double &u, double &v, double &tofZ) const;

	// A point of the colour frame in ToF coordinates and back.
	Eigen::Vector3d toTof(const Eigen::Vector3d &pColour) const;
	Eigen::Vector3d toColour(const Eigen::Vector3d &pTof) const;

private:
	LensModel colour_, tof_;
	Eigen::Matrix3d rotation_ = Eigen::Matrix3d::Identity();
	Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
};

} // namespace depthkey
