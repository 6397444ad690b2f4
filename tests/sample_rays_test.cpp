// The simulator's quadrant ray table (hal/sim/sample_rays.hpp) against the
// computation it replaced: every sample's float(normalise(undistort())),
// which the whole-grid table held. Tolerance: none, the floats bit for bit
// (the lecturer's coverage and depth come from them; any difference would
// move the simulator's pictures).
#include "hal/sim/camera_rig.hpp"
#include "hal/sim/sample_rays.hpp"

#include <cstring>
#include <gtest/gtest.h>

using namespace depthkey;
using depthkey::sim::SampleRays;

namespace {

// Every sample's ray stored as put() gets it, then each compared bitwise
// with the float of its exact ray; the number of samples that differ.
int mismatches(const LensModel &lens, int samples, bool fold, SampleRays &rays)
{
	const int w = lens.width * samples, h = lens.height * samples;
	rays.begin(lens, samples, fold);
	for (int j = 0; j < h; ++j)
		for (int i = 0; i < w; ++i)
			rays.put(i, j, SampleRays::exactRay(lens, samples, i, j));
	int wrong = 0;
	for (int j = 0; j < h; ++j)
		for (int i = 0; i < w; ++i) {
			const Eigen::Vector3d e = SampleRays::exactRay(lens, samples, i, j);
			const float want[3] = { float(e.x()), float(e.y()), float(e.z()) };
			const SampleRays::Ray r = rays.at(i, j);
			const float got[3] = { r.x, r.y, r.z };
			wrong += std::memcmp(want, got, sizeof want) != 0;
		}
	return wrong;
}

} // namespace

TEST(SampleRays, ColourAndTofGridsFoldToAQuadrantBitForBit)
{
	for (bool distortion : { true, false }) {
		CameraRig rig;
		rig.configure(640, 480, distortion, 60);
		SampleRays colour, tof;
		EXPECT_EQ(mismatches(rig.colour(), 1, true, colour), 0);
		EXPECT_TRUE(colour.exact());
		EXPECT_EQ(colour.storedRays(), 320u * 240u);
		EXPECT_EQ(mismatches(rig.tof(), 2, true, tof), 0); // the ToF's 2x2 samples a pixel
		EXPECT_TRUE(tof.exact());
		EXPECT_EQ(tof.storedRays(), 160u * 124u);
	}
}

TEST(SampleRays, OddSizesKeepTheirMiddleColumnAndRow)
{
	CameraRig rig;
	rig.configure(641, 481, true, 60);
	SampleRays rays;
	EXPECT_EQ(mismatches(rig.colour(), 1, true, rays), 0);
	EXPECT_EQ(rays.storedRays(), 321u * 241u);
}

TEST(SampleRays, AnOffCentreLensFoldsOnlyItsCentredAxis)
{
	CameraRig rig;
	rig.configure(640, 480, true, 60);
	LensModel lens = rig.colour();
	lens.cx += 0.3; // no column has an exact mirror
	SampleRays rays;
	EXPECT_EQ(mismatches(lens, 1, true, rays), 0);
	EXPECT_EQ(rays.storedRays(), 640u * 240u); // rows still fold: cy is centred
}

TEST(SampleRays, UnfoldedKeepsEverySample)
{
	CameraRig rig;
	rig.configure(640, 480, true, 60);
	SampleRays rays;
	EXPECT_EQ(mismatches(rig.colour(), 1, false, rays), 0);
	EXPECT_FALSE(rays.folded());
	EXPECT_EQ(rays.storedRays(), 640u * 480u);
}
