#include "algo/morphology.hpp"

#include <algorithm>

namespace depthkey {

namespace {

// One line (row or column, given by a start and a step) through a window of
// radius r: out = all set (erode) or any set (dilate) in [i - r, i + r],
// clamped to the line, from prefix counts of set pixels.
void filterLine(const uint8_t *in, uint8_t *out, int n, int step, int radius, bool erode,
		std::vector<int32_t> &prefix)
{
	prefix[0] = 0;
	for (int i = 0; i < n; ++i)
		prefix[i + 1] = prefix[i] + (in[i * step] != 0);
	for (int i = 0; i < n; ++i) {
		int a = std::max(0, i - radius), b = std::min(n - 1, i + radius);
		int set = prefix[b + 1] - prefix[a];
		bool on = erode ? set == b - a + 1 : set > 0;
		out[i * step] = on ? 255 : 0;
	}
}

void morph(const Gray8Image &in, int radius, Gray8Image &out, MorphologyScratch &scratch, bool erode)
{
	const int w = in.width(), h = in.height();
	out.resize(w, h);
	scratch.pass.resize(w, h);
	scratch.prefix.resize(std::max(w, h) + 1);
	for (int y = 0; y < h; ++y)
		filterLine(in.row(y), scratch.pass.row(y), w, 1, radius, erode, scratch.prefix);
	for (int x = 0; x < w; ++x)
		filterLine(scratch.pass.data() + x, out.data() + x, h, w, radius, erode, scratch.prefix);
}

} // namespace

void erodeSquare(const Gray8Image &in, int radius, Gray8Image &out, MorphologyScratch &scratch)
{
	morph(in, radius, out, scratch, true);
}

void dilateSquare(const Gray8Image &in, int radius, Gray8Image &out, MorphologyScratch &scratch)
{
	morph(in, radius, out, scratch, false);
}

int keepLargestComponent(Gray8Image &mask, ComponentScratch &scratch)
{
	const int w = mask.width(), h = mask.height();
	const int n = w * h;
	scratch.labels.assign(n, -1);
	scratch.stack.resize(n);
	uint8_t *m = mask.data();
	int32_t *labels = scratch.labels.data();
	int32_t *stack = scratch.stack.data();
	int bestLabel = -1, bestSize = 0, label = 0;
	for (int start = 0; start < n; ++start) {
		if (!m[start] || labels[start] >= 0)
			continue;
		// Each pixel is pushed once (labelled when pushed): n entries suffice.
		int top = 0, size = 0;
		labels[start] = label;
		stack[top++] = start;
		while (top) {
			int p = stack[--top];
			++size;
			int x = p % w;
			auto visit = [&](int q) {
				if (m[q] && labels[q] < 0) {
					labels[q] = label;
					stack[top++] = q;
				}
			};
			if (x > 0)
				visit(p - 1);
			if (x + 1 < w)
				visit(p + 1);
			if (p >= w)
				visit(p - w);
			if (p + w < n)
				visit(p + w);
		}
		if (size > bestSize) {
			bestSize = size;
			bestLabel = label;
		}
		++label;
	}
	for (int i = 0; i < n; ++i)
		m[i] = labels[i] == bestLabel && bestLabel >= 0 ? 255 : 0;
	return bestSize;
}

} // namespace depthkey
