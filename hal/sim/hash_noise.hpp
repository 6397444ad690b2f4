// Deterministic noise for the simulator: a hash of (seed, frame, pixel)
// rather than a generator, so any frame can be rendered alone, in any order,
// and gives the same pixels (same seed, same frames).
#pragma once

#include <cstdint>

namespace depthkey::sim {

// SplitMix64's finaliser: every input bit affects every output bit.
inline uint64_t mixHash(uint64_t x)
{
	x += 0x9E3779B97F4A7C15ull;
	x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
	x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
	return x ^ (x >> 31);
}

inline uint64_t hashKey(uint64_t a, uint64_t b)
{
	return mixHash(a ^ mixHash(b));
}

inline uint64_t hashKey(uint64_t a, uint64_t b, uint64_t c)
{
	return mixHash(hashKey(a, b) ^ (c * 0xD6E8FEB86659FD93ull));
}

// Uniform in [0, 1) from the top 24 bits.
inline float uniformFromHash(uint64_t h)
{
	return static_cast<float>(h >> 40) * (1.0f / 16777216.0f);
}

// Approximately standard normal: the sum of four 16-bit uniforms (Irwin-Hall,
// variance 4/12) scaled to unit variance. Tails end at +-3.46 sigma, which the
// statistics tests tolerate and which keeps it branch-free and cheap.
inline float gaussianFromHash(uint64_t h)
{
	constexpr float kScale = 1.7320508f / 65536.0f; // sqrt(3) / 2^16
	float sum = static_cast<float>(h & 0xFFFF) + static_cast<float>((h >> 16) & 0xFFFF) +
		    static_cast<float>((h >> 32) & 0xFFFF) + static_cast<float>(h >> 48);
	return (sum - 2.0f * 65535.0f) * kScale;
}

} // namespace depthkey::sim
