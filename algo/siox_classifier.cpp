#include "algo/siox_classifier.hpp"

#include <algorithm>
#include <cstring>
#include <limits>

namespace depthkey {

uint32_t integerSqrt(uint32_t v)
{
	// Bit-by-bit method: exact, 16 iterations, no floating point.
	uint32_t result = 0, bit = 1u << 30;
	while (bit > v)
		bit >>= 2;
	while (bit) {
		if (v >= result + bit) {
			v -= result + bit;
			result = (result >> 1) + bit;
		} else {
			result >>= 1;
		}
		bit >>= 2;
	}
	return result;
}

SioxClassifier::SioxClassifier(const QuantisedLab &lab) : lab_(lab), cache_(kQuantisedColours, 0)
{
}

void SioxClassifier::signaturesChanged()
{
	std::memset(cache_.data(), 0, cache_.size());
}

uint8_t SioxClassifier::decideLab(Lab16 lab) const
{
	if (board_.empty())
		return 255;
	if (lecturer_.empty())
		return 1;
	uint32_t dFg2 = lecturer_.nearest(lab), dBg2 = board_.nearest(lab);
	bool isLecturer = dFg2 <= dBg2;
	uint32_t dFg = integerSqrt(dFg2), dBg = integerSqrt(dBg2);
	uint32_t sum = dFg + dBg;
	// 1 + 254 * dBg / (dBg + dFg), rounded; sum == 0 means both distances 0.
	uint32_t c = sum ? 1 + (254 * dBg + sum / 2) / sum : 128;
	if (isLecturer)
		c = std::max<uint32_t>(c, kConfidenceLecturer);
	else
		c = std::min<uint32_t>(c, kConfidenceLecturer - 1);
	return uint8_t(c);
}

uint8_t SioxClassifier::decide(uint32_t quantised)
{
	uint8_t c = decideLab(lab_[quantised]);
	cache_[quantised] = c;
	return c;
}

} // namespace depthkey
