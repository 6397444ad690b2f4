// One camera's view of the simulated scene, sampled on a regular grid
// (samplesPerPixel^2 samples a pixel): a unit ray per sample through the
// distorted lens, what the static scene shows along it (computed once in
// configure()), and a z-buffer into which the lecturer's capsules are drawn
// every frame, only inside their screen bounding boxes.
//
// Capsule coverage is anti-aliased analytically: the ray's distance to the
// capsule's axis against its radius, over the sample's footprint, so edges
// carry fractional alpha without supersampling.
#pragma once

#include "hal/sim/camera_rig.hpp"
#include "hal/sim/scene_geometry.hpp"

#include <vector>

namespace depthkey::sim {

class RayGrid
{
public:
	// What a view keeps per sample besides depth and coverage: the colour
	// camera the colours and board texels, the ToF the reflectivities. Each
	// is 4-8 bytes a sample (2.4 MB of reflectivity at 640x480 that the
	// colour camera never read: issue 15); an accessor of a channel not kept
	// returns an empty vector.
	enum class Channels { Colour, Reflectivity };

	// cameraRotation/cameraOrigin: the camera's pose in the scene (colour)
	// frame, p_scene = rotation * p_camera + origin.
	void configure(const LensModel &lens, int samplesPerPixel, const Eigen::Matrix3d &cameraRotation,
		       const Eigen::Vector3d &cameraOrigin, const StaticScene &scene, Channels channels);

	int width() const { return width_; }
	int height() const { return height_; }
	int samplesPerPixel() const { return samples_; }
	size_t size() const { return staticZ_.size(); }

	// Static background per sample.
	const std::vector<float> &staticZ() const { return staticZ_; }          // camera-frame z, m
	const std::vector<int32_t> &boardTexel() const { return boardTexel_; }  // -1: not the board display
	const std::vector<Rgb8> &staticColour() const { return staticColour_; } // non-board surfaces, wall
	const std::vector<float> &staticReflectivity() const { return staticReflectivity_; }

	// Lecturer layer of the last drawCapsules(): nearest capsule's z and
	// shaded colour, coverage in [0, 1] (0 outside the dirty rectangle).
	void drawCapsules(const std::vector<Capsule> &sceneCapsules);
	const std::vector<float> &lecturerZ() const { return lecZ_; }
	const std::vector<float> &lecturerAlpha() const { return lecAlpha_; }
	const std::vector<Rgb8> &lecturerColour() const { return lecColour_; }
	const std::vector<float> &lecturerReflectivity() const { return lecReflectivity_; }
	// Bounding box [x0, x1) x [y0, y1) of what the last draw touched.
	int dirtyX0() const { return dirtyX0_; }
	int dirtyX1() const { return dirtyX1_; }
	int dirtyY0() const { return dirtyY0_; }
	int dirtyY1() const { return dirtyY1_; }

private:
	void clearDirty();
	void drawCapsule(const Capsule &c);

	LensModel lens_;
	bool colour_ = true; // Channels::Colour, else Reflectivity
	int samples_ = 1, width_ = 0, height_ = 0;
	float footprint_ = 0; // radians per sample
	Eigen::Matrix3f toCamera_ = Eigen::Matrix3f::Identity();
	Eigen::Vector3f origin_ = Eigen::Vector3f::Zero();
	std::vector<float> rayX_, rayY_, rayZ_;
	std::vector<float> staticZ_, staticReflectivity_;
	std::vector<int32_t> boardTexel_;
	std::vector<Rgb8> staticColour_;
	std::vector<float> lecZ_, lecAlpha_, lecReflectivity_;
	std::vector<Rgb8> lecColour_;
	int dirtyX0_ = 0, dirtyX1_ = 0, dirtyY0_ = 0, dirtyY1_ = 0;
};

} // namespace depthkey::sim
