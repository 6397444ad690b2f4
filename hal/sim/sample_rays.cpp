#include "hal/sim/sample_rays.hpp"

#include <Eigen/Geometry>

#include <cstring>

namespace depthkey::sim {

namespace {

double samplePosition(int index, int samples)
{
	return (index + 0.5) / samples - 0.5;
}

} // namespace

Eigen::Vector3d SampleRays::exactRay(const LensModel &lens, int samples, int i, int j)
{
	double xn, yn;
	lens.undistort(samplePosition(i, samples), samplePosition(j, samples), xn, yn);
	return Eigen::Vector3d(xn, yn, 1.0).normalized();
}

int SampleRays::layout(int count, int samples, double centre, double focal, bool fold, std::vector<int32_t> &slot,
		       std::vector<float> &sign)
{
	slot.assign(count, 0);
	sign.assign(count, 1.0f);
	int slots = 0;
	for (int i = 0; i < count; ++i) {
		const int mirror = count - 1 - i;
		// undistort()'s first step, compared exactly.
		const bool odd = (samplePosition(i, samples) - centre) / focal ==
				 -((samplePosition(mirror, samples) - centre) / focal);
		if (fold && mirror < i && odd) {
			slot[i] = slot[mirror];
			sign[i] = -1.0f;
		} else {
			slot[i] = slots++;
		}
	}
	return slots;
}

void SampleRays::begin(const LensModel &lens, int samples, bool fold)
{
	width_ = lens.width * samples;
	height_ = lens.height * samples;
	columnSlots_ = layout(width_, samples, lens.cx, lens.fx, fold, columnSlot_, columnSign_);
	rowSlots_ = layout(height_, samples, lens.cy, lens.fy, fold, rowSlot_, rowSign_);
	table_.assign(size_t(columnSlots_) * rowSlots_, Ray{ 0, 0, 0 });
	table_.shrink_to_fit();
	exact_ = true;
}

void SampleRays::put(int i, int j, const Eigen::Vector3d &ray)
{
	const Ray r{ static_cast<float>(ray.x()), static_cast<float>(ray.y()), static_cast<float>(ray.z()) };
	if (columnSign_[i] > 0 && rowSign_[j] > 0) { // owns its slot
		table_[size_t(rowSlot_[j]) * columnSlots_ + columnSlot_[i]] = r;
		return;
	}
	const Ray stored = at(i, j);
	// Bitwise: -0.0f and 0.0f differ in what the lecturer's arithmetic gives.
	auto same = [](float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; };
	if (!same(stored.x, r.x) || !same(stored.y, r.y) || !same(stored.z, r.z))
		exact_ = false;
}

} // namespace depthkey::sim
