#include "algo/colour_signature.hpp"

#include <algorithm>
#include <limits>

namespace depthkey {

namespace {

int component(const Lab16 &c, int axis)
{
	return axis == 0 ? c.l : axis == 1 ? c.a : c.b;
}

int64_t roundedDivide(int64_t n, int64_t d)
{
	return n >= 0 ? (n + d / 2) / d : -((-n + d / 2) / d);
}

struct Extent {
	int min, max;
};

Extent extentOf(const WeightedLab *p, size_t left, size_t right, int axis)
{
	Extent e{ component(p[left].lab, axis), component(p[left].lab, axis) };
	for (size_t i = left + 1; i < right; ++i) {
		int v = component(p[i].lab, axis);
		e.min = std::min(e.min, v);
		e.max = std::max(e.max, v);
	}
	return e;
}

// Splits [left, right) at floor((min + max) / 2) on the axis: returns the
// first index of the upper part. Both parts are non-empty since max > min.
size_t splitAtMiddle(WeightedLab *p, size_t left, size_t right, int axis, Extent e)
{
	int pivot = (e.min + e.max) >> 1; // arithmetic shift = floor for negatives too
	WeightedLab *mid = std::partition(p + left, p + right, [&](const WeightedLab &w) {
		return component(w.lab, axis) <= pivot;
	});
	return static_cast<size_t>(mid - p);
}

// The clustering recursion shared by both stages; a leaf [left, right) is
// written to p[clusters] (clusters <= left always: every earlier leaf held at
// least one point, so writing never overwrites an unvisited point).
struct Clustering {
	WeightedLab *p;
	int16_t limits[3];
	bool stageTwo;
	uint64_t total;
	size_t clusters = 0;

	void run(size_t left, size_t right, int depth)
	{
		int axis = depth % 3;
		Extent e = extentOf(p, left, right, axis);
		if (e.max - e.min > limits[axis]) {
			size_t mid = splitAtMiddle(p, left, right, axis, e);
			run(left, mid, depth + 1);
			run(mid, right, depth + 1);
			return;
		}
		leaf(left, right);
	}

	void leaf(size_t left, size_t right)
	{
		int64_t sl = 0, sa = 0, sb = 0;
		uint64_t weight = 0;
		for (size_t i = left; i < right; ++i) {
			// Stage one: weighted mean of samples. Stage two: the plain mean
			// of the stage-one centroids, as SIOX 1.13 does.
			int64_t w = stageTwo ? 1 : p[i].weight;
			sl += w * p[i].lab.l;
			sa += w * p[i].lab.a;
			sb += w * p[i].lab.b;
			weight += p[i].weight;
		}
		if (stageTwo && weight * 1000 < total)
			return; // under 0.1 % of the samples: noise
		int64_t n = stageTwo ? int64_t(right - left) : int64_t(weight);
		if (n == 0)
			return;
		p[clusters++] = { { int16_t(roundedDivide(sl, n)), int16_t(roundedDivide(sa, n)),
				    int16_t(roundedDivide(sb, n)) },
				  uint32_t(std::min<uint64_t>(weight, std::numeric_limits<uint32_t>::max())) };
	}
};

} // namespace

ColourSignature::ColourSignature()
{
	centroids_.reserve(kMaxCentroids);
	axis_.reserve(kMaxCentroids);
}

void ColourSignature::build(WeightedLab *points, size_t count, const SignatureLimits &limits)
{
	centroids_.clear();
	axis_.clear();
	uint64_t total = 0;
	for (size_t i = 0; i < count; ++i)
		total += points[i].weight;
	if (count == 0 || total == 0)
		return;

	Clustering one{ points, { limits.l, limits.a, limits.b }, false, total };
	one.run(0, count, 0);
	Clustering two{ points, { limits.l, limits.a, limits.b }, true, total };
	two.run(0, one.clusters, 0);

	size_t n = std::min(two.clusters, kMaxCentroids); // <= 1000 by the 0.1 % rule
	centroids_.assign(points, points + n);
	axis_.resize(n);
	buildTree(0, n);
}

void ColourSignature::buildTree(size_t lo, size_t hi)
{
	if (hi - lo <= 1) {
		if (hi > lo)
			axis_[lo] = 0;
		return;
	}
	int best = 0, bestSpread = -1;
	for (int axis = 0; axis < 3; ++axis) {
		Extent e = extentOf(centroids_.data(), lo, hi, axis);
		if (e.max - e.min > bestSpread) {
			bestSpread = e.max - e.min;
			best = axis;
		}
	}
	size_t mid = lo + (hi - lo) / 2;
	std::nth_element(centroids_.begin() + lo, centroids_.begin() + mid, centroids_.begin() + hi,
			 [best](const WeightedLab &x, const WeightedLab &y) {
				 return component(x.lab, best) < component(y.lab, best);
			 });
	axis_[mid] = uint8_t(best);
	buildTree(lo, mid);
	buildTree(mid + 1, hi);
}

void ColourSignature::search(size_t lo, size_t hi, Lab16 q, uint32_t &best) const
{
	if (lo >= hi)
		return;
	size_t mid = lo + (hi - lo) / 2;
	const WeightedLab &c = centroids_[mid];
	best = std::min(best, labDistanceSquared(q, c.lab));
	if (hi - lo == 1)
		return;
	int axis = axis_[mid];
	int64_t diff = component(q, axis) - component(c.lab, axis);
	bool lowFirst = diff <= 0;
	search(lowFirst ? lo : mid + 1, lowFirst ? mid : hi, q, best);
	if (uint64_t(diff * diff) < best)
		search(lowFirst ? mid + 1 : lo, lowFirst ? hi : mid, q, best);
}

uint32_t ColourSignature::nearest(Lab16 c) const
{
	uint32_t best = std::numeric_limits<uint32_t>::max();
	search(0, centroids_.size(), c, best);
	return best;
}

uint32_t ColourSignature::nearestBruteForce(Lab16 c) const
{
	uint32_t best = std::numeric_limits<uint32_t>::max();
	for (const WeightedLab &w : centroids_)
		best = std::min(best, labDistanceSquared(c, w.lab));
	return best;
}

} // namespace depthkey
