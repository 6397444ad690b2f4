// A colour signature (SIOX 1.13's ColorSignature): the centroids of a class's
// colours found by the two-stage modified k-d clustering after Rubner.
//
// Stage one splits the samples on axis depth % 3 (L, a, b) at the middle of
// the extent while the extent on that axis exceeds its limit, and turns each
// leaf into its (weighted) centroid. Stage two runs the same splitting on the
// stage-one centroids; a leaf becomes a signature centroid (the plain mean of
// its centroids, as the reference does) when it holds at least 0.1 % of all
// samples, else it is dropped as noise.
//
// Samples carry weights, so a histogram bin stands for all the samples in it
// (the reference's points are weight-1 samples). All in integer Lab16; the
// split pivot floor((min + max) / 2) sends exactly the values the float
// reference's (max - min) / 2 + min sends to the lower side.
#pragma once

#include "algo/lab_converter.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace depthkey {

struct WeightedLab {
	Lab16 lab;
	uint32_t weight;
};

// SIOX 1.13's defaults 0.64, 1.28, 2.56 in Lab16 units.
struct SignatureLimits {
	int16_t l = 64, a = 128, b = 256;
};

inline uint32_t labDistanceSquared(Lab16 p, Lab16 q)
{
	int32_t dl = p.l - q.l, da = p.a - q.a, db = p.b - q.b;
	return uint32_t(dl * dl) + uint32_t(da * da) + uint32_t(db * db);
}

class ColourSignature
{
public:
	// No centroid survives below 0.1 % of the samples, so there are at most
	// 1000: the storage is reserved here, once.
	static constexpr size_t kMaxCentroids = 1000;
	ColourSignature();

	// Clusters points[0..count); points is reordered and overwritten (it is
	// the clustering's work space). Allocation-free.
	void build(WeightedLab *points, size_t count, const SignatureLimits &limits = {});
	void clear() { centroids_.clear(); }

	size_t size() const { return centroids_.size(); }
	bool empty() const { return centroids_.empty(); }
	const WeightedLab &centroid(size_t i) const { return centroids_[i]; }

	// Squared distance to the nearest centroid (UINT32_MAX when empty), by a
	// k-d tree search; nearestBruteForce is its reference.
	uint32_t nearest(Lab16 c) const;
	uint32_t nearestBruteForce(Lab16 c) const;

private:
	void buildTree(size_t lo, size_t hi);
	void search(size_t lo, size_t hi, Lab16 q, uint32_t &best) const;

	std::vector<WeightedLab> centroids_; // in k-d tree order (median at the middle)
	std::vector<uint8_t> axis_;          // split axis of each tree node
};

} // namespace depthkey
