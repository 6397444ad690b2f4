// The daemon's keying-time histogram (daemon/keying_times.hpp) against the
// exact quantiles of the same times sorted: never below the exact value,
// and above it by at most one bucket's width (1/16 of it, plus 1 us).
#include "daemon/keying_times.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

using namespace depthkey;

TEST(KeyingTimes, BucketsCoverEveryTimeInOrder)
{
	uint64_t previousTop = 0;
	for (uint64_t us : { 0ull, 1ull, 15ull, 16ull, 17ull, 31ull, 32ull, 1000ull, 3999ull, 1234567ull, 1ull << 40 }) {
		const int b = KeyingTimes::bucketOf(us);
		EXPECT_GE(KeyingTimes::bucketTopUs(b), us) << us;
		EXPECT_LE(double(KeyingTimes::bucketTopUs(b) - us), double(us) / 16.0 + 1.0) << us;
		EXPECT_GE(KeyingTimes::bucketTopUs(b), previousTop) << us;
		previousTop = KeyingTimes::bucketTopUs(b);
	}
	// Contiguous: each bucket runs from just after the last one's top to its own.
	for (int b = 1; b < 16 * 40; ++b) {
		ASSERT_EQ(KeyingTimes::bucketOf(KeyingTimes::bucketTopUs(b - 1) + 1), b) << b;
		ASSERT_EQ(KeyingTimes::bucketOf(KeyingTimes::bucketTopUs(b)), b) << b;
	}
}

TEST(KeyingTimes, QuantilesMatchTheSortedTimesWithinABucket)
{
	std::mt19937 rng(7);
	std::lognormal_distribution<double> frameUs(std::log(3500.0), 0.35); // about 3.5 ms, a long tail
	KeyingTimes times;
	std::vector<uint64_t> all;
	for (int i = 0; i < 200000; ++i) {
		const uint64_t us = uint64_t(frameUs(rng)) + (i % 5000 == 0 ? 40000 : 0); // a rare stall
		times.add(us);
		all.push_back(us);
	}
	std::sort(all.begin(), all.end());
	EXPECT_EQ(times.count(), all.size());
	EXPECT_EQ(times.maxUs(), all.back());
	uint64_t sum = 0;
	for (uint64_t us : all)
		sum += us;
	EXPECT_EQ(times.sumUs(), sum);
	for (double q : { 0.0, 0.5, 0.9, 0.99, 0.999, 0.9999, 1.0 }) {
		const uint64_t exact = all[size_t(std::max(1.0, std::ceil(q * double(all.size())))) - 1];
		const uint64_t got = times.quantileUs(q);
		EXPECT_GE(got, exact) << "q " << q;
		EXPECT_LE(double(got), double(exact) * 17.0 / 16.0 + 1.0) << "q " << q;
	}
	EXPECT_EQ(KeyingTimes().quantileUs(0.5), 0u);
}
