// The depth evidence kernel (DepthSeeder::depthEvidence) against a double
// reference of the same log-likelihood ratio (tolerance: 2 units, one for
// the truncated variance, one for the truncated ratio), and what it says
// of clean, mixed and noisy depth.
#include <gtest/gtest.h>

#include "algo/depth_seeder.hpp"
#include "algo/static_background.hpp"

#include <algorithm>
#include <cmath>
#include <map>

using namespace depthkey;

namespace {

double evidenceReference(int d, int amplitude, int intensity, int zL, int zB)
{
	if (zB <= zL + StaticBackground::kToleranceMm)
		zB = zL + DepthSeeder::kUnknownBoardBehindMm;
	const double sigmaNoise = 7500.0 / std::sqrt(8.0) * std::sqrt(double(intensity)) / (2.0 * amplitude);
	double variance = double(DepthSeeder::kNoiseFloorMm) * DepthSeeder::kNoiseFloorMm;
	variance += amplitude > 0 ? sigmaNoise * sigmaNoise
				  : double(DepthSeeder::kNoAmplitudeSigmaMm) * DepthSeeder::kNoAmplitudeSigmaMm;
	const double nats = ((d - zB) * double(d - zB) - (d - zL) * double(d - zL)) / (2.0 * variance);
	return std::clamp(128.0 + DepthSeeder::kUnitsPerNat * nats, 1.0, 254.0);
}

// The simulated SR-2's board at the image centre and near a corner
// (amplitude, intensity = ambient + 1.5 amplitude).
constexpr int kCentreAmplitude = 6000, kCentreIntensity = 12000;
constexpr int kCornerAmplitude = 270, kCornerIntensity = 3400;

} // namespace

TEST(DepthEvidence, FixedPointMatchesTheDoubleReferenceWithinTwoUnits)
{
	std::map<int, int> histogram;
	int worst = 0;
	for (int zL = 600; zL <= 2400; zL += 450)
		for (int zB : { 0, zL + 100, zL + 450, zL + 1200 })
			for (int d = 400; d <= 4000; d += 37)
				for (int amplitude : { 0, 120, kCornerAmplitude, 1500, kCentreAmplitude, 30000 })
					for (int intensity : { 500, kCornerIntensity, kCentreIntensity, 60000 }) {
						const int fixed = DepthSeeder::depthEvidence(d, amplitude, intensity, zL, zB);
						const double ref = evidenceReference(d, amplitude, intensity, zL, zB);
						const int error = int(std::ceil(std::abs(fixed - ref) - 1e-9));
						histogram[error]++;
						worst = std::max(worst, error);
					}
	std::printf("depth evidence, fixed vs double, |error| histogram:");
	for (auto [e, n] : histogram)
		std::printf(" %d:%d", e, n);
	std::printf("\n");
	EXPECT_LE(worst, 2);
}

TEST(DepthEvidence, CleanDepthIsSureMixedAndNoisyDepthIsNot)
{
	const int zL = 1300, zB = 2000;
	// Clean depth on his surface or on the board: as sure as it gets.
	EXPECT_EQ(DepthSeeder::depthEvidence(zL, kCentreAmplitude, kCentreIntensity, zL, zB), 254);
	EXPECT_EQ(DepthSeeder::depthEvidence(zB, kCentreAmplitude, kCentreIntensity, zL, zB), 1);
	// A mixed pixel halfway (the halo, motion blur): neither.
	EXPECT_NEAR(DepthSeeder::depthEvidence((zL + zB) / 2, kCentreAmplitude, kCentreIntensity, zL, zB), 128, 1);
	// 10 cm nearer than halfway: clean depth (sigma 28 mm) says lecturer
	// clearly, the noisy corner (sigma 29 cm) hardly.
	const int d = (zL + zB) / 2 - 100;
	const int clean = DepthSeeder::depthEvidence(d, kCentreAmplitude, kCentreIntensity, zL, zB);
	const int noisy = DepthSeeder::depthEvidence(d, kCornerAmplitude, kCornerIntensity, zL, zB);
	EXPECT_GT(clean, 200);
	EXPECT_GT(noisy, 128);
	EXPECT_LT(noisy, 150);
	// No board learned behind him yet: it is taken 450 mm behind.
	EXPECT_EQ(DepthSeeder::depthEvidence(zL, kCentreAmplitude, kCentreIntensity, zL, 0),
		  DepthSeeder::depthEvidence(zL, kCentreAmplitude, kCentreIntensity, zL,
					     zL + DepthSeeder::kUnknownBoardBehindMm));
}
