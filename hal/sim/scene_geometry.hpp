// The shapes of the simulated lecture room, in the colour camera's frame
// (x right, y down, z forward, metres; the camera is 1.25 m above the floor).
// Static things (board, wall, desk, monitor, a calibration target) are
// axis-aligned or planar and rendered once per camera into a background
// table; the lecturer is a set of capsules re-posed every frame.
#pragma once

#include "algo/image.hpp"

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace depthkey::sim {

constexpr double kCameraHeightM = 1.25;  // floor is at y = +1.25

// A segment swept by a sphere: limbs, torso halves, head (a == b).
struct Capsule {
	Eigen::Vector3f a, b;
	float radius = 0;
	Rgb8 colour{};
	float reflectivity = 0.6f; // near infrared, for the ToF amplitude
	bool fast = false;         // moves fast: worth time samples for motion blur
};

// What covers a static rectangle: a plain colour, the board (display area
// with its texels, wall around it), or the calibration target's circles.
enum class QuadSurface { Plain, Board, CalibrationTarget };

// A rectangle: origin + s * edgeU + t * edgeV, s and t in [0, 1], edges
// orthogonal.
struct Quad {
	Eigen::Vector3d origin, edgeU, edgeV;
	Rgb8 colour{};
	float reflectivity = 0.5f;
	QuadSurface surface = QuadSurface::Plain;
};

// A printed planar calibration target: a grid of black circles on white,
// centre spacing and diameter in metres, at a pose in the colour frame.
struct CalibrationTarget {
	Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity(); // columns: target x, y, normal
	Eigen::Vector3d centre = Eigen::Vector3d(0, 0, 1.2);
	int columns = 7, rows = 5;
	double spacingM = 0.09, diameterM = 0.055;
	double marginM = 0.05;
	bool operator==(const CalibrationTarget &) const = default;
};

// The board plane and its frame: z = distance; the display area spans
// x in [kBoardLeft, kBoardRight], y in [kBoardTop, kBoardBottom]; wall around.
struct BoardGeometry {
	double distanceM = 2.0;
	static constexpr double kLeft = -1.6, kRight = 1.6;
	static constexpr double kTop = -0.78, kBottom = 0.52;
	static constexpr double kTexelM = 0.0025; // board raster: 2.5 mm
	static constexpr int texelColumns() { return static_cast<int>((kRight - kLeft) / kTexelM); }
	static constexpr int texelRows() { return static_cast<int>((kBottom - kTop) / kTexelM); }
};

// The desk (a lectern in the lecturer's depth interval, the paper's Figure 7)
// and the monitor on it (a dark, glossy screen: weak ToF return, noisy depth).
std::vector<Quad> deskQuads();

// Everything static: the board plane (with the wall), optionally the desk,
// optionally a calibration target in front of it all.
struct StaticScene {
	std::vector<Quad> quads;
	const CalibrationTarget *target = nullptr; // the circles of a CalibrationTarget quad
	static StaticScene build(double boardDistanceM, bool desk, const CalibrationTarget *target);
};

// The surface seen at a point of a quad: colour and near-infrared
// reflectivity; coverage-weighted over footprintM so circle edges are smooth.
void calibrationTargetSurface(const CalibrationTarget &target, double s, double t, double footprintM,
			      Rgb8 &colour, float &reflectivity);

} // namespace depthkey::sim
