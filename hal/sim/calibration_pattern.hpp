// The simulated calibration session: a printed board of black circles held
// at a pose in front of the simulated camera pair (hal/sim/camera_rig.hpp),
// rendered into the colour image and into the ToF depth and amplitude images
// with the paper's noise, so depthkey-calibrate --sim and its tests run on
// images whose true depth -> colour mapping (CameraRig::tofToColour) is known.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "algo/calibration_plan.hpp"
#include "algo/circle_grid_detector.hpp"
#include "algo/frames.hpp"
#include "hal/sim/camera_rig.hpp"
#include "hal/sim/scene_geometry.hpp"

namespace depthkey::sim {

// The printed board: an A1 sheet (841 x 594 mm) holds the default.
struct PatternBoard {
	GridSize grid;
	double spacingM = 0.12;         // between circle centres
	double diameterM = 0.07;
	double marginM = 0.05;          // white paper beyond the outer circles
};

struct PatternPose {
	Eigen::Vector3d centre = { 0, 0, 1.5 };         // board centre, colour camera frame
	double yawDeg = 0, pitchDeg = 0, rollDeg = 0;   // board turned from facing the camera
};

// The imaging conditions; the defaults are the simulator's (SimSettings).
struct PatternConditions {
	bool depthNoise = true;         // sigma = L / sqrt(8) * sqrt(I) / (2 A)
	double tofAmplitude = 6000;     // white paper at 2.2 m in the image centre
	double tofCornerAmplitude = 0.06;       // relative amplitude in the image corner
	double tofAmbient = 3000;       // background light in the intensity image
	double colourNoise = 3.0;       // sigma, 8-bit levels
	uint64_t seed = 1;
};

// The board at pose as the lecture simulator's scene object
// (LectureSimulator::setCalibrationTarget), the same geometry render() draws.
CalibrationTarget calibrationTarget(const PatternPose &pose, const PatternBoard &board);

class PatternRenderer
{
public:
	void configure(const CameraRig &rig, const PatternBoard &board, const PatternConditions &conditions);

	// The pose that puts the board at step's depth and place in the colour
	// image, its edge a little inside the image border, turned a few
	// degrees as a hand holds it (varying with index).
	PatternPose poseFor(const PatternStep &step, int index) const;

	// Both cameras' images of the board at pose; frame selects the noise.
	void render(const PatternPose &pose, uint64_t frame, ColourFrame &colour, DepthFrame &depth) const;

private:
	struct Hit {
		double t = 0;           // ray parameter: camera-frame z for rays with z = 1
		double reflectance = 0;
	};
	Hit trace(const Eigen::Vector3d &origin, const Eigen::Vector3d &dir, const PatternPose &pose,
		  const Eigen::Matrix3d &boardRotation) const;

	CameraRig rig_;
	PatternBoard board_;
	PatternConditions conditions_;
	// Unit-z ray directions per sample, camera frame, computed once.
	std::vector<Eigen::Vector2f> colourRays_, tofRays_;
};

} // namespace depthkey::sim
