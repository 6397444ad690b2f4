#include "tests/siox_reference.hpp"

#include "algo/trimap.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace depthkey::test {

LabD referenceLab(Rgb8 c)
{
	auto lin = [](int v) {
		double x = v / 255.0;
		return x > 0.04045 ? std::pow((x + 0.055) / 1.055, 2.4) : x / 12.92;
	};
	double r = lin(c.r), g = lin(c.g), b = lin(c.b);
	double x = (r * 0.4124 + g * 0.3576 + b * 0.1805) / 0.95047;
	double y = r * 0.2126 + g * 0.7152 + b * 0.0722;
	double z = (r * 0.0193 + g * 0.1192 + b * 0.9505) / 1.08883;
	auto f = [](double t) { return t > 0.008856 ? std::cbrt(t) : 7.787 * t + 16.0 / 116.0; };
	return { 116.0 * f(y) - 16.0, 500.0 * (f(x) - f(y)), 200.0 * (f(y) - f(z)) };
}

namespace {

double distSq(const LabD &p, const LabD &q)
{
	return (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]);
}

void cluster(std::vector<WeightedLabD> points, int depth, const LabD &limits, bool stageTwo,
	     double total, std::vector<WeightedLabD> &out)
{
	if (points.empty())
		return;
	int dim = depth % 3;
	double mn = points[0].lab[dim], mx = mn;
	for (const auto &p : points) {
		mn = std::min(mn, p.lab[dim]);
		mx = std::max(mx, p.lab[dim]);
	}
	if (mx - mn > limits[dim]) {
		double pivot = (mx - mn) / 2.0 + mn;
		std::vector<WeightedLabD> smaller, bigger;
		for (const auto &p : points)
			(p.lab[dim] <= pivot ? smaller : bigger).push_back(p);
		cluster(std::move(smaller), depth + 1, limits, stageTwo, total, out);
		cluster(std::move(bigger), depth + 1, limits, stageTwo, total, out);
		return;
	}
	LabD sum{ 0, 0, 0 };
	double weight = 0, count = 0;
	for (const auto &p : points) {
		double w = stageTwo ? 1.0 : p.weight; // stage two: plain mean of centroids
		for (int k = 0; k < 3; ++k)
			sum[k] += w * p.lab[k];
		count += w;
		weight += p.weight;
	}
	if (stageTwo && weight * 100.0 / total < 0.1)
		return;
	out.push_back({ { sum[0] / count, sum[1] / count, sum[2] / count }, weight });
}

} // namespace

std::vector<WeightedLabD> referenceSignature(std::vector<WeightedLabD> points, const LabD &limits,
					     bool roundStageOne)
{
	double total = 0;
	for (const auto &p : points)
		total += p.weight;
	std::vector<WeightedLabD> one, two;
	cluster(std::move(points), 0, limits, false, total, one);
	if (roundStageOne)
		for (auto &c : one)
			for (double &v : c.lab)
				v = v >= 0 ? std::floor(v + 0.5) : -std::floor(-v + 0.5);
	cluster(std::move(one), 0, limits, true, total, two);
	return two;
}

double referenceNearest(const std::vector<WeightedLabD> &signature, const LabD &c)
{
	double best = std::numeric_limits<double>::max();
	for (const auto &s : signature)
		best = std::min(best, distSq(c, s.lab));
	return best;
}

namespace {

struct Matrix {
	int w, h;
	std::vector<double> v;
	double &at(int i) { return v[size_t(i)]; }
};

void smoothcm(Matrix &m)
{
	const double f = 0.33;
	int w = m.w, h = m.h;
	auto &c = m.v;
	for (int y = 0; y < h; y++)
		for (int x = 0; x < w - 2; x++) {
			int i = y * w + x;
			c[i] = f * c[i] + f * c[i + 1] + f * c[i + 2];
		}
	for (int y = 0; y < h; y++)
		for (int x = w - 1; x >= 2; x--) {
			int i = y * w + x;
			c[i] = f * c[i - 2] + f * c[i - 1] + f * c[i];
		}
	for (int y = 0; y < h - 2; y++)
		for (int x = 0; x < w; x++) {
			int i = y * w + x;
			c[i] = f * c[i] + f * c[i + w] + f * c[i + 2 * w];
		}
	for (int y = h - 1; y >= 2; y--)
		for (int x = 0; x < w; x++) {
			int i = y * w + x;
			c[i] = f * c[i - 2 * w] + f * c[i - w] + f * c[i];
		}
}

void normalise(Matrix &m)
{
	double mx = 0;
	for (double v : m.v)
		mx = std::max(mx, v);
	if (mx <= 0.0 || mx == 1.0)
		return;
	for (double &v : m.v)
		v /= mx;
}

// The reference's in-place four-pass min / max (erode / dilate).
void morph(Matrix &m, bool erode)
{
	int w = m.w, h = m.h;
	auto &c = m.v;
	auto op = [erode](double a, double b) { return erode ? std::min(a, b) : std::max(a, b); };
	for (int y = 0; y < h; y++)
		for (int x = 0; x < w - 1; x++)
			c[y * w + x] = op(c[y * w + x], c[y * w + x + 1]);
	for (int y = 0; y < h; y++)
		for (int x = w - 1; x >= 1; x--)
			c[y * w + x] = op(c[y * w + x - 1], c[y * w + x]);
	for (int y = 0; y < h - 1; y++)
		for (int x = 0; x < w; x++)
			c[y * w + x] = op(c[y * w + x], c[(y + 1) * w + x]);
	for (int y = h - 1; y >= 1; y--)
		for (int x = 0; x < w; x++)
			c[y * w + x] = op(c[(y - 1) * w + x], c[y * w + x]);
}

void keepOnlyLargeComponents(Matrix &m, double threshold, double sizeFactor, const std::vector<char> &predefined)
{
	int w = m.w, h = m.h, n = w * h;
	std::vector<int> label(size_t(n), -1), sizes;
	std::vector<char> keep;
	int maxSize = 0, maxBlob = -1;
	for (int i = 0; i < n; i++) {
		if (label[i] != -1 || m.at(i) < threshold)
			continue;
		int cur = int(sizes.size()), size = 0;
		bool pre = false;
		std::vector<int> stack{ i };
		label[i] = cur;
		while (!stack.empty()) {
			int p = stack.back();
			stack.pop_back();
			++size;
			pre = pre || predefined[p];
			int x = p % w, y = p / w;
			int nb[4] = { x > 0 ? p - 1 : -1, x + 1 < w ? p + 1 : -1, y > 0 ? p - w : -1, y + 1 < h ? p + w : -1 };
			for (int q : nb)
				if (q >= 0 && label[q] == -1 && m.at(q) >= threshold) {
					label[q] = cur;
					stack.push_back(q);
				}
		}
		sizes.push_back(size);
		keep.push_back(pre);
		if (size > maxSize) {
			maxSize = size;
			maxBlob = cur;
		}
	}
	for (int i = 0; i < n; i++) {
		int l = label[i];
		if (l < 0)
			continue;
		if (sizeFactor == 0.0)
			m.at(i) = keep[l] ? 1.0 : 0.0;
		else if (sizes[l] * sizeFactor < maxSize && !keep[l])
			m.at(i) = 0.0;
		else if (l == maxBlob)
			m.at(i) = 1.0;
	}
}

void fillColorRegions(Matrix &m, const std::vector<LabD> &lab)
{
	int w = m.w, h = m.h, n = w * h;
	std::vector<char> visited(size_t(n), 0);
	for (int i = 0; i < n; i++) {
		if (visited[i] || m.at(i) < 0.5)
			continue;
		const LabD orig = lab[i];
		visited[i] = 1;
		m.at(i) = 1.0;
		std::vector<int> stack{ i };
		while (!stack.empty()) {
			int p = stack.back();
			stack.pop_back();
			int x = p % w, y = p / w;
			int nb[4] = { x > 0 ? p - 1 : -1, x + 1 < w ? p + 1 : -1, y > 0 ? p - w : -1, y + 1 < h ? p + w : -1 };
			for (int q : nb)
				if (q >= 0 && !visited[q] && std::sqrt(distSq(lab[q], orig)) < 1.0) {
					visited[q] = 1;
					m.at(q) = 1.0;
					stack.push_back(q);
				}
		}
	}
}

} // namespace

Gray8Image referenceSegmentate(const RgbImage &image, const Gray8Image &trimap, const ReferenceSioxOptions &options)
{
	const int w = image.width(), h = image.height(), n = w * h;
	Matrix cm{ w, h, std::vector<double>(size_t(n)) };
	std::vector<LabD> lab(static_cast<size_t>(n));
	std::vector<char> predefined(static_cast<size_t>(n), 0);
	std::vector<WeightedLabD> knownBg, knownFg;
	std::map<uint32_t, LabD> cache;
	for (int i = 0; i < n; i++) {
		Rgb8 c = image.data()[i];
		uint32_t key = uint32_t(c.r) << 16 | uint32_t(c.g) << 8 | c.b;
		auto it = cache.find(key);
		lab[i] = it != cache.end() ? it->second : (cache[key] = referenceLab(c));
		uint8_t t = trimap.data()[i];
		cm.at(i) = t == kTrimapLecturer ? 1.0 : t == kTrimapBoard ? 0.0 : 0.5;
		if (t == kTrimapBoard)
			knownBg.push_back({ lab[i], 1.0 });
		else if (t == kTrimapLecturer) {
			knownFg.push_back({ lab[i], 1.0 });
			predefined[i] = 1;
		}
	}
	auto bg = referenceSignature(knownBg), fg = referenceSignature(knownFg);
	for (int i = 0; i < n; i++) {
		if (cm.at(i) >= 0.8 || cm.at(i) <= 0.1)
			continue;
		double minBg = referenceNearest(bg, lab[i]), minFg = referenceNearest(fg, lab[i]);
		cm.at(i) = minBg < minFg ? 0.0 : 1.0;
	}
	smoothcm(cm);
	normalise(cm);
	morph(cm, true);
	keepOnlyLargeComponents(cm, 0.5, options.sizeFactorToKeep, predefined);
	for (int s = 0; s < options.smoothness; s++)
		smoothcm(cm);
	normalise(cm);
	for (double &v : cm.v)
		v = v >= 0.5 ? 1.0 : 0.0;
	keepOnlyLargeComponents(cm, 0.5, options.sizeFactorToKeep, predefined);
	fillColorRegions(cm, lab);
	morph(cm, false);
	Gray8Image out(w, h);
	for (int i = 0; i < n; i++)
		out.data()[i] = cm.at(i) >= 0.5 ? 255 : 0;
	return out;
}

} // namespace depthkey::test
