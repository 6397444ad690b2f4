#include "algo/guided_filter.hpp"

#include <algorithm>
#include <cstring>

namespace depthkey {

namespace {

// Integral image of f over the ROI into s, (w+1) x (h+1), modulo 2^32.
template<typename F>
void integrate(int w, int h, std::vector<uint32_t> &s, F f)
{
	const int stride = w + 1;
	std::fill(s.begin(), s.begin() + stride, 0u);
	for (int y = 0; y < h; ++y) {
		uint32_t row = 0;
		uint32_t *out = s.data() + size_t(y + 1) * stride, *above = out - stride;
		out[0] = 0;
		for (int x = 0; x < w; ++x) {
			row += uint32_t(f(x, y));
			out[x + 1] = above[x + 1] + row;
		}
	}
}

inline uint32_t box(const std::vector<uint32_t> &s, int stride, int x0, int y0, int x1, int y1)
{
	return s[size_t(y1) * stride + x1] - s[size_t(y0) * stride + x1] - s[size_t(y1) * stride + x0] +
	       s[size_t(y0) * stride + x0];
}

} // namespace

void GuidedFilter::configure(int radius, int eps)
{
	radius_ = std::clamp(radius, 1, kMaxRadius);
	eps_ = std::max(1, eps);
}

void GuidedFilter::filter(const RgbImage &colour, const Gray8Image &matte, const Roi &roi, Gray8Image &out)
{
	const int W = colour.width(), H = colour.height();
	out.resize(W, H);
	changed_ = 0;
	if (roi.empty())
		return;
	const int w = roi.x1 - roi.x0, h = roi.y1 - roi.y0, r = radius_, stride = w + 1;
	const size_t n = size_t(w) * h, sums = size_t(stride) * (h + 1);
	guide_.resize(W, H);
	near_.resize(W, H);
	// Sized for the whole image once (24 bytes per pixel), so that no frame
	// allocates whatever the ROI.
	for (auto *s : { &sumI_, &sumP_, &sumII_, &sumIP_ })
		if (s->size() < sums)
			s->resize(size_t(W + 1) * (H + 1));
	if (a_.size() < n) {
		a_.resize(size_t(W) * H);
		b_.resize(size_t(W) * H);
	}

	// Luma (r + 2g + b) / 4, and the pixels near an edge of the matte.
	for (int y = roi.y0; y < roi.y1; ++y) {
		const Rgb8 *c = colour.row(y);
		uint8_t *g = guide_.row(y), *nr = near_.row(y);
		for (int x = roi.x0; x < roi.x1; ++x) {
			g[x] = uint8_t((c[x].r + 2 * c[x].g + c[x].b + 2) >> 2);
			nr[x] = 0;
		}
	}
	auto I = [&](int x, int y) { return guide_.row(roi.y0 + y)[roi.x0 + x]; };
	auto P = [&](int x, int y) { return matte.row(roi.y0 + y)[roi.x0 + x]; };
	for (int y = 0; y < h; ++y)
		for (int x = 0; x < w; ++x) {
			const uint8_t p = P(x, y);
			const bool edge = (x + 1 < w && P(x + 1, y) != p) || (y + 1 < h && P(x, y + 1) != p);
			if (!edge)
				continue;
			// A window holding both pixels of this edge is centred within r
			// of them (its a, b are not 0, p); a pixel holding such a window
			// lies within 2r. Mark that square.
			for (int yy = std::max(0, y - 2 * r); yy <= std::min(h - 1, y + 2 * r + 1); ++yy)
				std::memset(near_.row(roi.y0 + yy) + roi.x0 + std::max(0, x - 2 * r), 1,
					    size_t(std::min(w - 1, x + 2 * r + 1) - std::max(0, x - 2 * r) + 1));
		}

	integrate(w, h, sumI_, I);
	integrate(w, h, sumP_, P);
	integrate(w, h, sumII_, [&](int x, int y) { return I(x, y) * I(x, y); });
	integrate(w, h, sumIP_, [&](int x, int y) { return I(x, y) * P(x, y); });

	auto window = [&](int x, int y, int &x0, int &y0, int &x1, int &y1) {
		x0 = std::max(0, x - r);
		y0 = std::max(0, y - r);
		x1 = std::min(w, x + r + 1);
		y1 = std::min(h, y + r + 1);
		return int64_t(x1 - x0) * (y1 - y0);
	};
	for (int y = 0; y < h; ++y)
		for (int x = 0; x < w; ++x) {
			const size_t i = size_t(y) * w + x;
			if (!near_.row(roi.y0 + y)[roi.x0 + x]) {
				a_[i] = 0;
				b_[i] = int32_t(P(x, y)) << 8;
				continue;
			}
			int x0, y0, x1, y1;
			const int64_t N = window(x, y, x0, y0, x1, y1);
			const int64_t sI = box(sumI_, stride, x0, y0, x1, y1), sP = box(sumP_, stride, x0, y0, x1, y1);
			const int64_t sII = box(sumII_, stride, x0, y0, x1, y1), sIP = box(sumIP_, stride, x0, y0, x1, y1);
			// a = (N sIP - sI sP) / (N sII - sI^2 + eps N^2), in Q16; then
			// b = (sP - a sI) / N in Q8. Both rounded to nearest.
			const int64_t cov = N * sIP - sI * sP, var = N * sII - sI * sI + int64_t(eps_) * N * N;
			const int64_t num = cov * 65536;
			const int64_t a = (num >= 0 ? num + var / 2 : num - var / 2) / var;
			const int64_t bNum = (sP << 16) - a * sI; // Q16 * N
			const int64_t bDen = N * 256;
			a_[i] = int32_t(a);
			b_[i] = int32_t((bNum >= 0 ? bNum + bDen / 2 : bNum - bDen / 2) / bDen);
		}
	// The moments' integrals are done with: reuse them for a and b.
	std::vector<uint32_t> &sumA = sumII_, &sumB = sumIP_;
	integrate(w, h, sumA, [&](int x, int y) { return uint32_t(a_[size_t(y) * w + x]); });
	integrate(w, h, sumB, [&](int x, int y) { return uint32_t(b_[size_t(y) * w + x]); });
	for (int y = 0; y < h; ++y) {
		uint8_t *o = out.row(roi.y0 + y) + roi.x0;
		const uint8_t *nr = near_.row(roi.y0 + y) + roi.x0;
		for (int x = 0; x < w; ++x) {
			const uint8_t p = P(x, y);
			if (!nr[x]) {
				o[x] = p;
				continue;
			}
			int x0, y0, x1, y1;
			const int64_t N = window(x, y, x0, y0, x1, y1);
			const int64_t sA = int32_t(box(sumA, stride, x0, y0, x1, y1));
			const int64_t sB = int32_t(box(sumB, stride, x0, y0, x1, y1));
			// q = (sA I / 2^16 + sB / 2^8) / N, rounded.
			const int64_t num = sA * I(x, y) + sB * 256, den = N * 65536;
			const int64_t q = (num >= 0 ? num + den / 2 : num - den / 2) / den;
			o[x] = uint8_t(std::clamp<int64_t>(q, 0, 255));
			changed_ += o[x] != p;
		}
	}
}

} // namespace depthkey
