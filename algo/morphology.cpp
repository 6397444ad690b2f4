#include "algo/morphology.hpp"

#include "algo/mask_rows.hpp"

#include <algorithm>
#include <cstring>

namespace depthkey {

namespace {

// Outside the image the edge pixel repeats, so a window clamped to the image
// and a window over the padded row agree: min / max over the same values.
void morph(const Gray8Image &in, int radius, Gray8Image &out, MorphologyScratch &scratch, bool erode,
	   KernelPath path)
{
	const int w = in.width(), h = in.height();
	out.resize(w, h);
	if (w == 0 || h == 0)
		return;
	scratch.pass.resize(w, h);
	scratch.padded.resize(size_t(w) + 2 * radius);
	const MaskRowFn combine = maskRow(path, erode);
	uint8_t *pad = scratch.padded.data();
	for (int y = 0; y < h; ++y) {
		const uint8_t *src = in.row(y);
		for (int x = 0; x < w; ++x)
			pad[radius + x] = src[x] ? 255 : 0;
		std::memset(pad, pad[radius], size_t(radius));
		std::memset(pad + radius + w, pad[radius + w - 1], size_t(radius));
		uint8_t *dst = scratch.pass.row(y);
		std::memcpy(dst, pad, size_t(w));
		for (int k = 1; k <= 2 * radius; ++k)
			combine(dst, pad + k, w);
	}
	for (int y = 0; y < h; ++y) {
		uint8_t *dst = out.row(y);
		const int y0 = std::max(0, y - radius), y1 = std::min(h - 1, y + radius);
		std::memcpy(dst, scratch.pass.row(y0), size_t(w));
		for (int yy = y0 + 1; yy <= y1; ++yy)
			combine(dst, scratch.pass.row(yy), w);
	}
}

} // namespace

void erodeSquare(const Gray8Image &in, int radius, Gray8Image &out, MorphologyScratch &scratch, KernelPath path)
{
	morph(in, radius, out, scratch, true, path);
}

void dilateSquare(const Gray8Image &in, int radius, Gray8Image &out, MorphologyScratch &scratch, KernelPath path)
{
	morph(in, radius, out, scratch, false, path);
}

int labelComponents(const Gray8Image &mask, ComponentScratch &scratch)
{
	const int w = mask.width(), h = mask.height(), stride = w + 2;
	scratch.sizes.clear();
	if (w == 0 || h == 0)
		return 0;
	// Labels live in a grid one pixel larger on every side whose border is
	// never set, so the flood visits the 4 neighbours without bounds checks.
	scratch.labels.assign(size_t(stride) * (h + 2), kNoComponent);
	scratch.stack.resize(size_t(w) * h);
	// At most one component per two pixels (a checkerboard): room for the
	// worst case once, so a noisier frame than any before never allocates.
	const size_t maxComponents = (size_t(w) * h + 1) / 2;
	scratch.sizes.reserve(maxComponents);
	scratch.counts.reserve(2 * maxComponents);
	constexpr int32_t kUnvisited = -1;
	const uint8_t *m = mask.data();
	int32_t *labels = scratch.labels.data();
	int32_t *stack = scratch.stack.data();
	for (int y = 0; y < h; ++y) {
		const uint8_t *row = m + size_t(y) * w;
		int32_t *l = labels + size_t(y + 1) * stride + 1;
		for (int x = 0; x < w; ++x)
			l[x] = row[x] ? kUnvisited : kNoComponent;
	}
	int label = 0;
	for (int y = 0; y < h; ++y) {
		const int rowStart = (y + 1) * stride + 1;
		for (int start = rowStart; start < rowStart + w; ++start) {
			if (labels[start] != kUnvisited)
				continue;
			// Each pixel is pushed once (labelled when pushed): w * h entries suffice.
			int top = 0, size = 0;
			labels[start] = label;
			stack[top++] = start;
			while (top) {
				const int p = stack[--top];
				++size;
				for (int q : { p - 1, p + 1, p - stride, p + stride }) {
					if (labels[q] == kUnvisited) {
						labels[q] = label;
						stack[top++] = q;
					}
				}
			}
			scratch.sizes.push_back(size);
			++label;
		}
	}
	return label;
}

void keepComponent(Gray8Image &mask, const ComponentScratch &scratch, int label)
{
	const int w = mask.width(), h = mask.height(), stride = w + 2;
	for (int y = 0; y < h; ++y) {
		uint8_t *row = mask.row(y);
		const int32_t *l = scratch.labels.data() + size_t(y + 1) * stride + 1;
		for (int x = 0; x < w; ++x)
			row[x] = l[x] == label && label >= 0 ? 255 : 0;
	}
}

int keepComponentsTouching(Gray8Image &mask, const Gray8Image &seeds, ComponentScratch &scratch)
{
	const int w = mask.width(), h = mask.height(), stride = w + 2;
	if (w == 0 || h == 0 || seeds.width() != w || seeds.height() != h)
		return 0;
	// A grid one pixel larger on every side (never in the mask), so the
	// flood reads the 4 neighbours without bounds checks: 0 = not in the
	// mask, 1 = in it, 2 = reached from a seed.
	constexpr int32_t kIn = 1, kKept = 2;
	scratch.labels.assign(size_t(stride) * (h + 2), 0);
	scratch.stack.resize(size_t(w) * h);
	int32_t *grid = scratch.labels.data(), *stack = scratch.stack.data();
	for (int y = 0; y < h; ++y) {
		const uint8_t *row = mask.row(y);
		int32_t *g = grid + size_t(y + 1) * stride + 1;
		for (int x = 0; x < w; ++x)
			g[x] = row[x] ? kIn : 0;
	}
	int top = 0, size = 0;
	for (int y = 0; y < h; ++y) {
		const uint8_t *s = seeds.row(y);
		const int rowStart = (y + 1) * stride + 1;
		for (int x = 0; x < w; ++x) {
			if (!s[x] || grid[rowStart + x] != kIn)
				continue;
			grid[rowStart + x] = kKept;
			stack[top++] = rowStart + x;
			while (top) {
				const int p = stack[--top];
				++size;
				for (int q : { p - 1, p + 1, p - stride, p + stride })
					if (grid[q] == kIn) {
						grid[q] = kKept;
						stack[top++] = q;
					}
			}
		}
	}
	for (int y = 0; y < h; ++y) {
		uint8_t *row = mask.row(y);
		const int32_t *g = grid + size_t(y + 1) * stride + 1;
		for (int x = 0; x < w; ++x)
			row[x] = g[x] == kKept ? 255 : 0;
	}
	return size;
}

} // namespace depthkey
