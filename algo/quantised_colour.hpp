// Colours quantised to 6 bits per channel (262144 cells of 4x4x4 code
// values): the key of the colour histograms and of SIOX's decision cache, so
// that classifying a pixel is one shift-and-or and one table lookup. A cell
// is about 1.5 L* units wide, finer than the sensor noise of a webcam.
#pragma once

#include "algo/image.hpp"
#include "algo/lab_converter.hpp"

#include <cstdint>

namespace depthkey {

constexpr int kQuantBits = 6;
constexpr uint32_t kQuantisedColours = 1u << (3 * kQuantBits);

inline uint32_t quantiseColour(Rgb8 c)
{
	return (uint32_t(c.r >> 2) << 12) | (uint32_t(c.g >> 2) << 6) | uint32_t(c.b >> 2);
}

// The colour at the middle of a cell (code values 4q .. 4q+3 -> 4q+2).
inline Rgb8 quantisedCentre(uint32_t index)
{
	return { uint8_t(((index >> 12) & 63) * 4 + 2), uint8_t(((index >> 6) & 63) * 4 + 2),
		 uint8_t((index & 63) * 4 + 2) };
}

// Lab16 of a cell's centre, converted when asked. Only the colours of the
// cells looked up are ever needed (a histogram's non-empty cells when a
// signature is derived, a decision cache miss), never a pixel's own
// lookup, so no table: one conversion (a few table lookups and multiplies
// in LabConverter) is small beside the two k-d tree searches of a cache miss,
// and a table of every cell cost 1.5 MB of resident memory (issue 15).
class QuantisedLab
{
public:
	Lab16 operator[](uint32_t index) const
	{
		Rgb8 c = quantisedCentre(index);
		return converter_.convert(c.r, c.g, c.b);
	}

private:
	LabConverter converter_;
};

} // namespace depthkey
