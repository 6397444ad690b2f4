// sRGB (D65, 2 degree observer) -> CIELAB in fixed point, the conversion SIOX
// 1.13 uses (its Utils.rgbToClab, the easyrgb.com formulas).
//
// Output is Lab16: L*, a*, b* times kLabScale (100), so L* 0..100 is 0..10000
// and SIOX's cluster limits 0.64 / 1.28 / 2.56 become exactly 64 / 128 / 256.
// Every difference of two Lab16 fits int16 and every squared distance fits
// int32 (max about 8.6e8).
//
// Fixed point, from tables built once:
//   sRGB -> linear light, Q24, 256 entries;
//   linear -> X/Xn, Y/Yn, Z/Zn with the white division folded into Q14
//   coefficients (each row sums to 1.0), 64-bit products;
//   f(t) = t^(1/3) (t > 0.008856) or 7.787 t + 16/116, Q24, a 4097-entry table
//   over t in [0, 1] with linear interpolation.
// Q24 rather than Q16 because a* = 500 (fx - fy) amplifies the error of f
// 50000-fold in Lab16 units: Q16 left 0.08 a* units in dark colours.
// Tested against the double formulas for every 3rd code value in each channel:
// max error stated in tests/lab_converter_test.cpp.
#pragma once

#include <array>
#include <cstdint>

namespace depthkey {

constexpr int kLabScale = 100;

struct Lab16 {
	int16_t l, a, b;
	bool operator==(const Lab16 &) const = default;
};

class LabConverter
{
public:
	LabConverter(); // builds the tables (pure computation, cannot fail)

	Lab16 convert(uint8_t r, uint8_t g, uint8_t b) const;

private:
	static constexpr int kCubeRootSteps = 4096;
	static constexpr int64_t kOne = int64_t(1) << 24;
	int32_t cubeRoot(int64_t t) const;

	std::array<int32_t, 256> linear_;
	std::array<int32_t, kCubeRootSteps + 1> cubeRoot_;
};

} // namespace depthkey
