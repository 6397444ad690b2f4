// How long keying a colour frame takes in the daemon: its work wherever it
// ran, the pipeline on the keying worker (timed there) and the board warp,
// preview hand-off, shared memory and webcam writes on the loop, not the
// time it waited for the worker (daemon/keying_worker.hpp): the figure
// that says whether a box keeps up, and the soak's per-frame time
// (tests/soak/).
//
// A fixed histogram with 16 buckets per power of two of microseconds (at
// most 1/16 = 6 % wide), so quantiles stay exact to a bucket over any
// number of frames, in constant memory, with no allocation per frame.
#pragma once

#include <array>
#include <cstdint>

namespace depthkey {

class KeyingTimes
{
public:
	void add(uint64_t us);
	uint64_t count() const { return count_; }
	uint64_t sumUs() const { return sumUs_; }
	uint64_t maxUs() const { return maxUs_; }
	// The smallest bucket bound at or above which a fraction q of the frames
	// lie (never more than the largest time seen); 0 without frames.
	uint64_t quantileUs(double q) const;

	// Bucket of a time, and the largest time in a bucket (for the tests).
	static int bucketOf(uint64_t us);
	static uint64_t bucketTopUs(int bucket);

private:
	static constexpr int kSub = 16; // buckets per power of two
	static constexpr int kBuckets = kSub * 61;
	std::array<uint64_t, kBuckets> buckets_{};
	uint64_t count_ = 0, sumUs_ = 0, maxUs_ = 0;
};

} // namespace depthkey
