#include "algo/lab_converter.hpp"

#include <cmath>

namespace depthkey {

namespace {

// sRGB -> XYZ (D65) as in SIOX 1.13, each row divided by the white point
// (Xn = 0.95047, Yn = 1, Zn = 1.08883), in Q14: round(coefficient * 16384).
constexpr int kQ14 = 16384;
constexpr double kMatrix[3][3] = {
	{ 0.4124 / 0.95047, 0.3576 / 0.95047, 0.1805 / 0.95047 },
	{ 0.2126, 0.7152, 0.0722 },
	{ 0.0193 / 1.08883, 0.1192 / 1.08883, 0.9505 / 1.08883 },
};

// Round to nearest; all coefficients are positive.
constexpr int32_t q14(double c)
{
	return static_cast<int32_t>(c * kQ14 + 0.5);
}

constexpr int32_t kXr = q14(kMatrix[0][0]), kXg = q14(kMatrix[0][1]), kXb = q14(kMatrix[0][2]);
constexpr int32_t kYr = q14(kMatrix[1][0]), kYg = q14(kMatrix[1][1]), kYb = q14(kMatrix[1][2]);
constexpr int32_t kZr = q14(kMatrix[2][0]), kZg = q14(kMatrix[2][1]), kZb = q14(kMatrix[2][2]);

double labF(double t)
{
	return t > 0.008856 ? std::cbrt(t) : 7.787 * t + 16.0 / 116.0;
}

} // namespace

LabConverter::LabConverter()
{
	for (int i = 0; i < 256; ++i) {
		double c = i / 255.0;
		double lin = c > 0.04045 ? std::pow((c + 0.055) / 1.055, 2.4) : c / 12.92;
		linear_[i] = static_cast<int32_t>(std::lround(lin * kOne));
	}
	for (int i = 0; i <= kCubeRootSteps; ++i)
		cubeRoot_[i] = static_cast<int32_t>(std::lround(labF(double(i) / kCubeRootSteps) * kOne));
}

int32_t LabConverter::cubeRoot(int64_t t) const
{
	// Slightly above 1.0 can happen by rounding; the table ends at 1.0.
	if (t >= kOne)
		return cubeRoot_[kCubeRootSteps];
	if (t < 0)
		t = 0;
	// 2^24 / 4096 = 4096 input steps per table step.
	int64_t i = t >> 12, frac = t & 4095;
	return int32_t(cubeRoot_[i] + (((cubeRoot_[i + 1] - cubeRoot_[i]) * frac + 2048) >> 12));
}

Lab16 LabConverter::convert(uint8_t r, uint8_t g, uint8_t b) const
{
	int64_t lr = linear_[r], lg = linear_[g], lb = linear_[b];
	// Q24 * Q14 -> Q38, back to Q24 with rounding (64-bit: table building
	// and cache misses only, never per pixel).
	int64_t x = (lr * kXr + lg * kXg + lb * kXb + (1 << 13)) >> 14;
	int64_t y = (lr * kYr + lg * kYg + lb * kYb + (1 << 13)) >> 14;
	int64_t z = (lr * kZr + lg * kZg + lb * kZb + (1 << 13)) >> 14;
	int64_t fx = cubeRoot(x), fy = cubeRoot(y), fz = cubeRoot(z);
	// L = 116 fy - 16, a = 500 (fx - fy), b = 200 (fy - fz), times 100, f in Q24.
	auto scaled = [](int64_t f, int64_t factor) {
		int64_t v = f * factor;
		return (v + (int64_t(1) << 23)) >> 24; // floor(v / 2^24 + 0.5)
	};
	Lab16 out;
	out.l = static_cast<int16_t>(scaled(fy, 11600) - 1600);
	out.a = static_cast<int16_t>(scaled(fx - fy, 50000));
	out.b = static_cast<int16_t>(scaled(fy - fz, 20000));
	return out;
}

} // namespace depthkey
