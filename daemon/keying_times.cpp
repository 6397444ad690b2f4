#include "daemon/keying_times.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

namespace depthkey {

// 0..15 us have a bucket each; above, the top 5 bits of the time choose
// one of 16 buckets in its power of two.
int KeyingTimes::bucketOf(uint64_t us)
{
	if (us < uint64_t(kSub))
		return int(us);
	const int msb = 63 - std::countl_zero(us); // >= 4
	const int shift = msb - 4;
	return std::min(kBuckets - 1, (shift + 1) * kSub + int((us >> shift) - kSub));
}

uint64_t KeyingTimes::bucketTopUs(int bucket)
{
	if (bucket < kSub)
		return uint64_t(bucket);
	const int shift = bucket / kSub - 1;
	const uint64_t low = uint64_t(kSub + bucket % kSub) << shift;
	return low + (uint64_t(1) << shift) - 1;
}

void KeyingTimes::add(uint64_t us)
{
	buckets_[size_t(bucketOf(us))]++;
	count_++;
	sumUs_ += us;
	maxUs_ = std::max(maxUs_, us);
}

uint64_t KeyingTimes::quantileUs(double q) const
{
	if (count_ == 0)
		return 0;
	// The rank of the frame at q, 1-based: ceil(q n), at least the first.
	const uint64_t rank = std::max<uint64_t>(1, uint64_t(std::ceil(std::clamp(q, 0.0, 1.0) * double(count_))));
	uint64_t seen = 0;
	for (int b = 0; b < kBuckets; ++b) {
		seen += buckets_[size_t(b)];
		if (seen >= rank)
			return std::min(bucketTopUs(b), maxUs_);
	}
	return maxUs_;
}

} // namespace depthkey
