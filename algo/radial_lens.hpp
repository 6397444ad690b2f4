// The colour camera's radial lens distortion, as the board calibration fits
// it: a webcam's barrel bends the board's straight edges, which no
// homography can follow (1.55 board px RMS on the simulator's lens), so the
// board map is  seen colour px --undistort--> ideal colour px --H--> board px.
//
// Brown's two radial terms about the image centre, in units of a nominal
// focal length of one image width (any scale works; H absorbs it):
//   seen = c + f * u * (1 + k1 |u|^2 + k2 |u|^4),  u = (ideal - c) / f.
// distort() is closed-form, so the compositor's per-pixel map (board px ->
// ideal -> seen) costs nothing per frame; undistort() is a few Newton steps,
// used on the calibration's circle centres and the ROI's corners only.
// k1 = k2 = 0 is a pinhole: both maps are the identity.
#pragma once

namespace depthkey {

// Brown's radial terms backwards, shared by this lens and the simulator's
// (hal/sim/camera_rig.cpp): Newton on the radius, r (1 + k1 r^2 + k2 r^4) =
// rd, from r = rd. r is always written; false when it did not settle on a
// root where the lens is still monotonic (past its fold).
bool undistortRadius(double rd, double k1, double k2, double &r);

struct RadialLens {
	double cx = 0, cy = 0, f = 1; // centre and nominal focal length, px
	double k1 = 0, k2 = 0;
	// d(seen radius)/d(ideal radius) below this counts as folded.
	static constexpr double kMinSlope = 0.05;

	// The lens for a colour image of the given size with these terms.
	static RadialLens forImage(int width, int height, double k1, double k2)
	{
		return RadialLens{ (width - 1) / 2.0, (height - 1) / 2.0, double(width), k1, k2 };
	}
	bool isPinhole() const { return k1 == 0 && k2 == 0; }

	// False past the radius where the lens folds back (a strong barrel
	// term's image of far-out points lands inside the picture again):
	// such a point is not seen, whatever pixel the formula gives.
	bool distort(double ix, double iy, double &x, double &y) const
	{
		const double ux = (ix - cx) / f, uy = (iy - cy) / f;
		const double r2 = ux * ux + uy * uy;
		const double s = 1.0 + r2 * (k1 + k2 * r2);
		x = cx + f * ux * s;
		y = cy + f * uy * s;
		return 1.0 + r2 * (3.0 * k1 + 5.0 * k2 * r2) > kMinSlope;
	}

	// False when Newton does not settle (a lens so strong that the radius
	// folds back inside the image: not a camera, a corrupt file).
	bool undistort(double x, double y, double &ix, double &iy) const;
};

} // namespace depthkey
