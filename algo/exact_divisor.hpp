// Division by a divisor fixed for a frame or longer, as a multiply and a
// shift (issue 28: no division per pixel), with the quotient of the
// division it replaces bit for bit.
//
// For 0 <= n < 2^31 and 1 <= d < 2^31, with l = ceil(log2 d), s = 31 + l
// and m = ceil(2^s / d) (at most 2^32, so n m < 2^63 fits):
//   n m / 2^s = n / d + n e / (d 2^s),  e = m d - 2^s in [0, d),
// and the second term is below 2^31 2^l / (d 2^(31 + l)) = 1 / d, too little
// to carry n / d past the next integer: floor(n m / 2^s) = floor(n / d)
// (Granlund and Montgomery, PLDI 1994, theorem 4.2).
#pragma once

#include <cstdint>

namespace depthkey {

class ExactDivisor
{
public:
	static constexpr int kNumeratorBits = 31; // |n| < 2^31

	// d >= 1.
	void set(uint32_t d)
	{
		int l = 0;
		while ((uint64_t(1) << l) < d)
			++l;
		shift_ = kNumeratorBits + l;
		multiplier_ = ((uint64_t(1) << shift_) + d - 1) / d;
	}

	// floor(n / d) for 0 <= n < 2^31.
	uint32_t floor(uint32_t n) const { return uint32_t((n * multiplier_) >> shift_); }
	// n / d truncated towards zero, as C++'s / does, for |n| < 2^31.
	int32_t truncate(int32_t n) const { return n >= 0 ? int32_t(floor(uint32_t(n))) : -int32_t(floor(uint32_t(-n))); }

private:
	uint64_t multiplier_ = uint64_t(1) << kNumeratorBits;
	int shift_ = kNumeratorBits;
};

} // namespace depthkey
