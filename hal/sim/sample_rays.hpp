// The unit ray through every sample of a simulated camera's grid, as floats
// for drawing the lecturer, kept for one quadrant of the grid (issue 15: 12
// bytes a sample, 3.7 MB at 640x480, now a quarter of it).
//
// Why a quadrant is exact: a sample's ray is normalise(undistort(x, y), 1),
// and undistort() works on (x - cx) / fx, (y - cy) / fy through the radius
// alone. Where a column's normalised coordinate is the exact negative of
// its mirror column's (the simulator's lenses are centred on the image,
// cx = (width - 1) / 2, and the sample positions are sums of halves and
// quarters: exact), every later step is odd in x and even in y, so the
// mirror's ray is the same floats with x negated; rows likewise. A column
// or row without an exact mirror keeps a slot of its own, and put() checks
// every mirrored ray against the one computed for it anyway: exact() false
// means the caller stores the grid unfolded.
#pragma once

#include "hal/sim/camera_rig.hpp"

#include <cstdint>
#include <vector>

namespace depthkey::sim {

class SampleRays
{
public:
	struct Ray {
		float x, y, z;
	};

	// Sample (i, j) of a grid of samples^2 a pixel sits at pixel
	// ((i + 0.5) / samples - 0.5, (j + 0.5) / samples - 0.5); its unit ray in
	// the camera's frame, in double (the static scene is intersected so).
	static Eigen::Vector3d exactRay(const LensModel &lens, int samples, int i, int j);

	// Lays out the table for the lens's grid; fold false stores every sample.
	void begin(const LensModel &lens, int samples, bool fold = true);
	// Every sample's exactRay(), in row-major order: stored when it owns its
	// slot, else compared with what its mirror stored.
	void put(int i, int j, const Eigen::Vector3d &ray);
	// False when a mirrored ray was not its mirror's exactly.
	bool exact() const { return exact_; }
	bool folded() const { return columnSlots_ < width_ || rowSlots_ < height_; }
	size_t storedRays() const { return table_.size(); }

	Ray at(int i, int j) const
	{
		const Ray &r = table_[size_t(rowSlot_[j]) * columnSlots_ + columnSlot_[i]];
		return { r.x * columnSign_[i], r.y * rowSign_[j], r.z };
	}

private:
	// Each column's (row's) slot and the sign of x (y) there; the number of
	// slots.
	static int layout(int count, int samples, double centre, double focal, bool fold, std::vector<int32_t> &slot,
			  std::vector<float> &sign);

	int width_ = 0, height_ = 0, columnSlots_ = 0, rowSlots_ = 0;
	std::vector<int32_t> columnSlot_, rowSlot_;
	std::vector<float> columnSign_, rowSign_;
	std::vector<Ray> table_;
	bool exact_ = true;
};

} // namespace depthkey::sim
