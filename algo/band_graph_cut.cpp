#include "algo/band_graph_cut.hpp"

#include "algo/band_scan.hpp"
#include "algo/siox_classifier.hpp"
#include "algo/trimap.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <vector>

// OpenCV's GCGraph is a header-only template: its one link-time need is
// cv::error() behind CV_Assert, which would bring libopencv_core (and the
// GL, X11 and LAPACK libraries it loads, some 4.5 MB resident) back into
// the daemon, which links no OpenCV. Its assertions check what cut()
// guarantees by construction (vertices that exist and differ, weights >= 0,
// at least one edge), so a failure is a bug here: abort, as assert() would.
// (cvdef.h: its types and MIN, no code.)
#include <climits>
#include <opencv2/core/cvdef.h>
#define CV_Assert(expr) \
	do { \
		if (!(expr)) \
			std::abort(); \
	} while (0)
#include <opencv2/imgproc/detail/gcgraph.hpp>
#undef CV_Assert

namespace depthkey {

void BandGraphCut::configure(int smoothness, int edgeSigma)
{
	smoothness_ = std::max(0, smoothness);
	weightByDistance2_.clear();
	if (!smoothness_)
		return;
	// Built once per configuration (floating point here is setup, not
	// per-pixel work): every squared distance until the weight rounds to 0.
	const double sigma = std::max(1, edgeSigma), twoSigma2 = 2.0 * sigma * sigma;
	for (int d2 = 0;; ++d2) {
		const int w = int(std::lround(smoothness_ * std::exp(-d2 / twoSigma2)));
		if (w <= 0)
			break;
		weightByDistance2_.push_back(w);
	}
}

int BandGraphCut::edgeWeight(Rgb8 a, Rgb8 b) const
{
	const int dr = int(a.r) - b.r, dg = int(a.g) - b.g, db = int(a.b) - b.b;
	const size_t d2 = size_t(dr * dr + dg * dg + db * db);
	return d2 < weightByDistance2_.size() ? weightByDistance2_[d2] : 0;
}

void BandGraphCut::cut(const RgbImage &colour, const Gray8Image &trimap, const std::vector<BandSpan> &spans,
		       const uint8_t *confidence, uint8_t *decisions)
{
	if (spans.empty())
		return;
	const BandSpan &last = spans.back();
	const int pixels = last.first + (last.x1 - last.x0);
	// The flow is at most the sum of the source capacities, (127 + 4 *
	// cut_smoothness) a pixel: 32-bit weights whenever that fits (every band
	// at the default smoothness, even the whole 640x480 frame), 64-bit
	// beyond. The graph is the frame's largest block and comes and goes with
	// it (GCGraph has no reset): 32-bit weights make it 80 bytes a band pixel
	// instead of 104, and the cut is the same, integer arithmetic without
	// overflow either way.
	if (int64_t(pixels) * (int64_t(kConfidenceLecturer) + 4 * int64_t(smoothness_)) <= INT32_MAX)
		cutWith<int32_t>(colour, trimap, spans, pixels, confidence, decisions);
	else
		cutWith<int64_t>(colour, trimap, spans, pixels, confidence, decisions);
}

template<typename Weight>
void BandGraphCut::cutWith(const RgbImage &colour, const Gray8Image &trimap, const std::vector<BandSpan> &spans,
			   int pixels, const uint8_t *confidence, uint8_t *decisions)
{
	const int w = colour.width(), h = colour.height();
	// The first span of each row (spans are row-major), for the pixel below.
	rowFirstSpan_.assign(size_t(h) + 2, int(spans.size()));
	for (int i = int(spans.size()) - 1; i >= 0; --i)
		rowFirstSpan_[size_t(spans[size_t(i)].y)] = i;
	for (int y = h; y >= 0; --y)
		rowFirstSpan_[size_t(y)] = std::min(rowFirstSpan_[size_t(y)], rowFirstSpan_[size_t(y) + 1]);

	cv::detail::GCGraph<Weight> graph(unsigned(pixels), unsigned(4 * pixels));
	int edges = 0;
	terminal_.resize(size_t(pixels));
	for (int k = 0; k < pixels; ++k)
		graph.addVtx();
	for (const BandSpan &s : spans) {
		const Rgb8 *row = colour.row(s.y);
		const uint8_t *t = trimap.row(s.y);
		const bool hasUp = s.y > 0, hasDown = s.y + 1 < h;
		const Rgb8 *up = hasUp ? colour.row(s.y - 1) : nullptr, *down = hasDown ? colour.row(s.y + 1) : nullptr;
		const uint8_t *tUp = hasUp ? trimap.row(s.y - 1) : nullptr, *tDown = hasDown ? trimap.row(s.y + 1) : nullptr;
		int below = rowFirstSpan_[size_t(s.y) + 1];
		const int belowEnd = rowFirstSpan_[size_t(s.y) + 2];
		for (int x = s.x0, k = s.first; x < s.x1; ++x, ++k) {
			// Cost of calling it board (source side cut) and lecturer.
			const int data = int(confidence[k]) - int(kConfidenceLecturer);
			int toLecturer = std::max(data, 0), toBoard = std::max(-data, 0);
			// A fixed neighbour pulls with the edge's weight.
			auto fixed = [&](uint8_t label, int weight) {
				if (label == kTrimapLecturer)
					toLecturer += weight;
				else if (label == kTrimapBoard)
					toBoard += weight;
			};
			if (x > 0 && isTrimapSeed(t[x - 1]))
				fixed(t[x - 1], edgeWeight(row[x], row[x - 1]));
			if (x + 1 < w) {
				const int weight = edgeWeight(row[x], row[x + 1]);
				if (x + 1 < s.x1) {
					graph.addEdges(k, k + 1, weight, weight);
					++edges;
				} else {
					fixed(t[x + 1], weight);
				}
			}
			if (hasUp && isTrimapSeed(tUp[x]))
				fixed(tUp[x], edgeWeight(row[x], up[x]));
			if (hasDown) {
				const int weight = edgeWeight(row[x], down[x]);
				if (isTrimapSeed(tDown[x])) {
					fixed(tDown[x], weight);
				} else {
					// A band pixel below: in one of the next row's spans.
					while (below < belowEnd && spans[size_t(below)].x1 <= x)
						++below;
					if (below < belowEnd && spans[size_t(below)].x0 <= x) {
						graph.addEdges(k, spans[size_t(below)].first + (x - spans[size_t(below)].x0), weight,
							       weight);
						++edges;
					}
				}
			}
			graph.addTermWeights(k, toLecturer, toBoard);
			terminal_[size_t(k)] = toLecturer - toBoard;
		}
	}
	if (!edges) {
		// No two band pixels touch: each is its own cut (GCGraph's
		// maxFlow() refuses a graph without edges).
		for (int k = 0; k < pixels; ++k)
			decisions[k] = terminal_[size_t(k)] > 0 ? 255 : 0;
		return;
	}
	graph.maxFlow();
	for (int k = 0; k < pixels; ++k)
		decisions[k] = graph.inSourceSegment(k) ? 255 : 0;
}

} // namespace depthkey
