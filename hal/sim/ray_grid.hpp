// One camera's view of the simulated scene, sampled on a regular grid
// (samplesPerPixel^2 samples a pixel): a unit ray per sample through the
// distorted lens, what the static scene shows along it (computed once in
// configure()), and the lecturer's capsules drawn one row of samples at a
// time, only inside their screen bounding boxes.
//
// Memory (issue 15): the lecturer is drawn into one row of buffers that the
// caller consumes before asking for the next row, not into whole-frame
// z/alpha/colour planes (11 bytes a sample at 640x480: 3.4 MB), and the rays
// are kept for one quadrant of the grid only (sample_rays.hpp). Both give
// the same floats as the whole-frame planes did: each sample's result
// depends only on the capsules in their order, never on other samples.
//
// Capsule coverage is anti-aliased analytically: the ray's distance to the
// capsule's axis against its radius, over the sample's footprint, so edges
// carry fractional alpha without supersampling.
#pragma once

#include "hal/sim/camera_rig.hpp"
#include "hal/sim/sample_rays.hpp"
#include "hal/sim/scene_geometry.hpp"
#include "hal/sim/row_palette.hpp"

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
	size_t size() const { return static_cast<size_t>(width_) * height_; }
	const SampleRays &rays() const { return rays_; }

	// Static background per sample: camera-frame z (m) along sample row j,
	// valid until another row's is asked for (drawRow(j) asks for row j).
	const float *staticZRow(int j) const { return staticZ_.row(j); }
	// The static colours (non-board surfaces, wall), the board texel each
	// sample sees (-1: not the board display) and the reflectivities are
	// handed over once: the simulator folds them into tables of its own
	// (sim::ColourBackdrop, the ToF's amplitudes) and the grid keeps no copy.
	std::vector<Rgb8> takeStaticColour() { return std::move(staticColour_); }
	std::vector<int32_t> takeBoardTexel() { return std::move(boardTexel_); }
	std::vector<float> takeStaticReflectivity() { return std::move(staticReflectivity_); }

	// The lecturer of one frame: poses the capsules in this camera's frame
	// and finds the samples each may cover. Then drawRow(j) for the rows
	// wanted, in any order.
	void setCapsules(const std::vector<Capsule> &sceneCapsules);
	// Bounding box [x0, x1) x [y0, y1) of the samples the capsules may cover.
	int dirtyX0() const { return dirtyX0_; }
	int dirtyX1() const { return dirtyX1_; }
	int dirtyY0() const { return dirtyY0_; }
	int dirtyY1() const { return dirtyY1_; }

	// The lecturer along sample row j: the nearest capsule's z and shaded
	// colour (or reflectivity), coverage in [0, 1]. Every sample of the row
	// is valid (alpha 0 where no capsule is); colour/reflectivity only where
	// alpha > 0. Valid until the next drawRow() or setCapsules().
	struct Row {
		const float *z, *alpha;
		const Rgb8 *colour;         // Channels::Colour
		const float *reflectivity;  // Channels::Reflectivity
	};
	Row drawRow(int j);

private:
	// A capsule in camera coordinates with the constants every sample uses.
	struct PosedCapsule {
		Eigen::Vector3f a, ba;
		float r, C, aa, aba;
		Rgb8 colour;
		float reflectivity;
		int x0, x1, y0, y1; // samples it may cover
	};
	bool pose(const Capsule &scene, PosedCapsule &out) const;
	void drawSpan(const PosedCapsule &c, int j, int x0, int x1, const float *staticZ);

	LensModel lens_;
	bool colour_ = true; // Channels::Colour, else Reflectivity
	int samples_ = 1, width_ = 0, height_ = 0;
	float footprint_ = 0; // radians per sample
	Eigen::Matrix3f toCamera_ = Eigen::Matrix3f::Identity();
	Eigen::Vector3f origin_ = Eigen::Vector3f::Zero();
	SampleRays rays_;
	RowPalette<float> staticZ_; // about a byte a sample: few depths a row (row_palette.hpp)
	std::vector<float> staticReflectivity_;
	std::vector<int32_t> boardTexel_;
	std::vector<Rgb8> staticColour_;
	std::vector<PosedCapsule> posed_;
	// One row of the lecturer; [rowX0_, rowX1_) is what the last drawRow()
	// may have written, cleared before the next.
	std::vector<float> rowZ_, rowAlpha_, rowReflectivity_;
	std::vector<Rgb8> rowColour_;
	int rowX0_ = 0, rowX1_ = 0;
	int dirtyX0_ = 0, dirtyX1_ = 0, dirtyY0_ = 0, dirtyY1_ = 0;
};

} // namespace depthkey::sim
