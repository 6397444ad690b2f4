#include "algo/coarse_to_fine_cut.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <cstring>

// OpenCV's GCGraph is a header-only template: its one link-time need is
// cv::error() behind CV_Assert, which would bring libopencv_core (and the
// GL, X11 and LAPACK libraries it loads, some 4.5 MB resident) into the
// daemon, which links no OpenCV. Its assertions check what cutWith()
// guarantees by construction (vertices that exist and differ, weights >= 0,
// at least one edge), so a failure is a bug here: abort, as assert() would.
// (cvdef.h: its types and MIN, no code.)
#include <opencv2/core/cvdef.h>
#define CV_Assert(expr) \
	do { \
		if (!(expr)) \
			std::abort(); \
	} while (0)
#include <opencv2/imgproc/detail/gcgraph.hpp>
#undef CV_Assert

namespace depthkey {

struct CoarseToFineCut::Graphs {
	cv::detail::GCGraph<int32_t> narrow;
	cv::detail::GCGraph<int64_t> wide;
};

CoarseToFineCut::CoarseToFineCut() : graphs_(std::make_unique<Graphs>())
{
}

CoarseToFineCut::~CoarseToFineCut() = default;

void CoarseToFineCut::solve(CutGrid &fine, int levels, const DeferredLinks *deferred)
{
	levels = std::clamp(levels, 0, kMaxLevels);
	cellsCut_.fill(0);
	// Coarsen while it pays: each level a quarter of the last.
	int depth = 0;
	for (CutGrid *finer = &fine; depth < levels; finer = &coarse_[size_t(depth)]) {
		CutGrid &coarser = coarse_[size_t(depth) + 1];
		if (coarsen(*finer, coarser) < kMinCoarseCells)
			break;
		++depth;
	}
	CutGrid &coarsest = depth ? coarse_[size_t(depth)] : fine;
	int vertices = 0;
	if (active_.size() < coarsest.cells())
		active_.resize(coarsest.cells()); // grows once: no steady-state allocation
	for (int y = 0; y < coarsest.height; ++y)
		for (CutGrid::Run run = coarsest.nextRun(y, 0); run.x0 < coarsest.width;
		     run = coarsest.nextRun(y, run.x1))
			for (int x = run.x0; x < run.x1; ++x) {
				const size_t c = size_t(y) * size_t(coarsest.width) + size_t(x);
				active_[size_t(vertices)] = int32_t(c);
				coarsest.node[c] = vertices++;
			}
	if (deferred && !depth)
		deferred->weigh(fine, active_.data(), vertices);
	cutActive(coarsest, vertices);
	cellsCut_[size_t(depth)] = size_t(vertices);
	for (int level = depth - 1; level >= 0; --level) {
		CutGrid &finer = level ? coarse_[size_t(level)] : fine;
		const CutGrid &coarser = coarse_[size_t(level) + 1];
		markEdge(coarser);
		vertices = activate(finer, coarser);
		if (deferred && !level)
			deferred->weigh(fine, active_.data(), vertices);
		cutActive(finer, vertices);
		cellsCut_[size_t(level)] = size_t(vertices);
	}
}

size_t CoarseToFineCut::coarsen(const CutGrid &fine, CutGrid &coarse)
{
	const int cw = (fine.width + 1) / 2, ch = (fine.height + 1) / 2;
	coarse.reset(cw, ch);
	size_t freeCells = 0;
	for (int y = 0; y < fine.height; ++y) {
		const size_t row = size_t(y) * size_t(fine.width);
		const size_t coarseRow = size_t(y / 2) * size_t(cw);
		const bool crossesDown = y & 1; // the link below leaves the block
		for (CutGrid::Run run = fine.nextRun(y, 0); run.x0 < fine.width; run = fine.nextRun(y, run.x1))
			for (int x = run.x0; x < run.x1; ++x) {
				const size_t c = row + size_t(x);
				const size_t b = coarseRow + size_t(x) / 2; // a shift: x >= 0
				if (coarse.state[b] != CutGrid::kFree) {
					coarse.state[b] = CutGrid::kFree;
					coarse.unary[b] = coarse.right[b] = coarse.down[b] = 0;
					coarse.touches[b] = 0;
					++freeCells;
				}
				coarse.unary[b] += fine.unary[c];
				coarse.touches[b] |= fine.touches[c];
				// Links inside the block cost nothing: its pixels share a label.
				if (x & 1)
					coarse.right[b] += fine.right[c];
				if (crossesDown)
					coarse.down[b] += fine.down[c];
			}
	}
	return freeCells;
}

void CoarseToFineCut::markEdge(const CutGrid &coarse)
{
	const int w = coarse.width, h = coarse.height;
	const size_t n = coarse.cells();
	if (edge_.size() < n) {
		edge_.resize(n);
		marks_.resize(n);
	}
	// A cell on the decided edge: a free neighbour or a fixed one on the
	// other side. Fixed cells are not on it. Two free neighbours that
	// differ are both on it: each pair is looked at once, from its left or
	// upper cell (the pairs to the left and above were marked before).
	std::fill(edge_.begin(), edge_.begin() + std::ptrdiff_t(n), uint8_t(0));
	for (int y = 0; y < h; ++y)
		for (CutGrid::Run run = coarse.nextRun(y, 0); run.x0 < w; run = coarse.nextRun(y, run.x1))
			for (int x = run.x0; x < run.x1; ++x) {
				const size_t c = size_t(y) * size_t(w) + size_t(x);
				const uint8_t l = coarse.label[c];
				const uint8_t otherSide = l ? CutGrid::kTouchesBoard : CutGrid::kTouchesLecturer;
				uint8_t onEdge = edge_[c] | uint8_t((coarse.touches[c] & otherSide) != 0);
				// Within a run the cell to the right is free.
				if (x + 1 < run.x1 && coarse.label[c + 1] != l)
					onEdge = edge_[c + 1] = 1;
				const size_t below = c + size_t(w);
				if (y + 1 < h && coarse.state[below] == CutGrid::kFree && coarse.label[below] != l)
					onEdge = edge_[below] = 1;
				edge_[c] = onEdge;
			}
	// Grown by margin_ cells (a square): rows first into marks_, then
	// columns back into edge_ (coarse grids are small). Margin 0 (shipped)
	// is the edge itself.
	const int m = margin_;
	if (!m)
		return;
	for (int y = 0; y < h; ++y) {
		const uint8_t *e = edge_.data() + size_t(y) * size_t(w);
		uint8_t *out = marks_.data() + size_t(y) * size_t(w);
		for (int x = 0; x < w; ++x) {
			uint8_t any = 0;
			for (int i = std::max(0, x - m), end = std::min(w - 1, x + m); i <= end && !any; ++i)
				any = e[i];
			out[x] = any;
		}
	}
	for (int y = 0; y < h; ++y)
		for (int x = 0; x < w; ++x) {
			uint8_t any = 0;
			for (int j = std::max(0, y - m), end = std::min(h - 1, y + m); j <= end && !any; ++j)
				any = marks_[size_t(j) * size_t(w) + size_t(x)];
			edge_[size_t(y) * size_t(w) + size_t(x)] = any;
		}
}

int CoarseToFineCut::activate(CutGrid &fine, const CutGrid &coarse)
{
	if (active_.size() < fine.cells())
		active_.resize(fine.cells()); // grows once: no steady-state allocation
	int vertices = 0;
	for (int y = 0; y < fine.height; ++y) {
		const size_t row = size_t(y) * size_t(fine.width);
		const size_t coarseRow = size_t(y / 2) * size_t(coarse.width);
		for (CutGrid::Run run = fine.nextRun(y, 0); run.x0 < fine.width; run = fine.nextRun(y, run.x1))
			for (int x = run.x0; x < run.x1; ++x) {
				const size_t c = row + size_t(x);
				const size_t b = coarseRow + size_t(x) / 2; // a shift: x >= 0
				if (edge_[b]) {
					active_[size_t(vertices)] = int32_t(c);
					fine.node[c] = vertices++;
				} else {
					fine.node[c] = -1;
					fine.label[c] = coarse.label[b];
				}
			}
	}
	return vertices;
}

void CoarseToFineCut::cutActive(CutGrid &grid, int vertices)
{
	if (!vertices)
		return;
	// A free neighbour decided at a coarser level pulls as a fixed one does;
	// folded into the unary term first, so that the flow's bound is known
	// before the graph's weight type is chosen.
	// Only the vertices' cells are walked (active_, row-major), not the
	// level's grid: at the finest level they are a few percent of it. A
	// link is non-zero only between free cells of one row or column
	// (cut_grid.hpp), so a link's weight says that its neighbour exists.
	const size_t w = size_t(grid.width);
	int64_t sourceSum = 0, sinkSum = 0;
	for (int v = 0; v < vertices; ++v) {
		const size_t c = size_t(active_[size_t(v)]);
		int32_t u = grid.unary[c];
		auto pull = [&](size_t q, int32_t link) {
			if (link && grid.node[q] < 0)
				u += grid.label[q] ? link : -link;
		};
		if (c > 0 && grid.state[c - 1] == CutGrid::kFree)
			pull(c - 1, grid.right[c - 1]);
		pull(c + 1, grid.right[c]);
		if (c >= w && grid.state[c - w] == CutGrid::kFree)
			pull(c - w, grid.down[c - w]);
		pull(c + w, grid.down[c]);
		grid.unary[c] = u;
		(u > 0 ? sourceSum : sinkSum) += u > 0 ? u : -u;
	}
	// The flow is at most the smaller of the terminals' capacities; a
	// residual link holds its weight plus what flowed back through it.
	if (std::min(sourceSum, sinkSum) <= INT32_MAX / 2)
		cutWith<int32_t>(graphs_->narrow, grid, vertices);
	else
		cutWith<int64_t>(graphs_->wide, grid, vertices);
}

template<typename Weight, typename Graph>
void CoarseToFineCut::cutWith(Graph &graph, CutGrid &grid, int vertices)
{
	static const Graph empty;
	graph = empty; // copy-assigned: keeps the vectors' capacity
	graph.create(unsigned(vertices), unsigned(4 * vertices));
	for (int v = 0; v < vertices; ++v)
		graph.addVtx();
	const size_t w = size_t(grid.width);
	int edges = 0;
	for (int v = 0; v < vertices; ++v) {
		const size_t c = size_t(active_[size_t(v)]);
		const int32_t u = grid.unary[c];
		graph.addTermWeights(v, Weight(std::max(u, 0)), Weight(std::max(-u, 0)));
		// A zero link carries no flow (the search skips it): left out.
		if (const int32_t right = grid.right[c]; right && grid.node[c + 1] >= 0) {
			graph.addEdges(v, grid.node[c + 1], Weight(right), Weight(right));
			++edges;
		}
		if (const int32_t down = grid.down[c]; down && grid.node[c + w] >= 0) {
			graph.addEdges(v, grid.node[c + w], Weight(down), Weight(down));
			++edges;
		}
	}
	if (edges)
		graph.maxFlow(); // GCGraph refuses a graph without edges
	for (int v = 0; v < vertices; ++v) {
		const size_t c = size_t(active_[size_t(v)]);
		grid.label[c] = edges ? uint8_t(graph.inSourceSegment(v)) : uint8_t(grid.unary[c] > 0);
	}
}

} // namespace depthkey
