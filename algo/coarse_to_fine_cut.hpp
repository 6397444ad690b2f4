// The band's minimum cut, solved coarse to fine: the multilevel banded graph
// cut of Lombaert, Sun, Grady and Xu (ICCV 2005). The energy of the finest
// grid (algo/cut_grid.hpp) is summed over 2x2 blocks into a grid a quarter
// the size, and again, `levels` times: a coarse cell is the same energy with
// its four pixels forced to one label (links inside a block vanish, links
// across blocks add up), so nothing is approximated but the forcing. The
// coarsest grid is cut whole; then each finer grid is cut again only within
// `margin` coarse cells of the coarse decision's edge (where a coarse cell's
// label differs from a neighbour's, a fixed seed's, or is next to one),
// every other cell taking its coarse cell's label, which pulls on the cells
// being cut as a fixed neighbour does.
//
// Why: the whole band's graph (80 bytes a band pixel, 4.9 MB for the
// lecture's 60,000 pixels at 640x480) does not fit in a cache and the cut
// was three quarters of a frame; the edge the cut decides is a line, so the
// band near it grows with the image's width, not its area. What it can
// miss: a structure thinner than a coarse cell and away from every coarse
// edge (a finger alone in the band), which the coarse cut may give to the
// board; the accuracy gate measures it (docs/accuracy.md).
//
// The max-flow is OpenCV's GCGraph (Boykov-Kolmogorov), in 32-bit weights
// where the flow cannot overflow them. Its graphs are kept between frames
// (emptied by copy-assignment, which keeps the vectors' capacity), so a
// steady state allocates only maxFlow()'s own list of orphans.
#pragma once

#include "algo/cut_grid.hpp"

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

namespace depthkey {

class CoarseToFineCut
{
public:
	static constexpr int kMaxLevels = 4;
	// A level coarser than this many free cells is not made: its cut would
	// cost less than the bookkeeping.
	static constexpr size_t kMinCoarseCells = 512;

	CoarseToFineCut();
	~CoarseToFineCut();

	// margin: coarse cells around a coarse edge cut again (0: the edge's own).
	void configure(int margin) { margin_ = margin < 0 ? 0 : margin; }

	// Weighs the links of the finest grid that its builder deferred
	// (CutGrid::kLinkDeferred, only ever inside a 2x2 block: right at an
	// even x, down at an even y), for the cells listed, which are given a
	// vertex; the others' links inside their block are never read.
	class DeferredLinks
	{
	public:
		virtual void weigh(CutGrid &fine, const int32_t *cells, int count) const = 0;

	protected:
		~DeferredLinks() = default;
	};

	// Labels every free cell of `fine` (fine.label), which the caller has
	// filled: state, unary, right, down and touches at its free cells (with
	// `deferred`, the links inside a block may be kLinkDeferred). Its
	// `node` and `label` are overwritten; its unary too (the pulls of
	// neighbours decided at a coarser level are added in). levels 0 (or a
	// band too small to coarsen) cuts the whole grid at once.
	void solve(CutGrid &fine, int levels, const DeferredLinks *deferred = nullptr);

	// Free cells cut at each level of the last solve(), coarsest last (for
	// tests and the bench's breakdown).
	const std::array<size_t, kMaxLevels + 1> &cellsCut() const { return cellsCut_; }

private:
	struct Graphs;

	// Sums fine into coarse (2x2 blocks); returns coarse's free cells.
	static size_t coarsen(const CutGrid &fine, CutGrid &coarse);
	// Marks the coarse cells within margin_ of the coarse decision's edge.
	void markEdge(const CutGrid &coarse);
	// Fine cells under marked coarse cells get a graph vertex; the others
	// take their coarse cell's label. Returns the vertices.
	int activate(CutGrid &fine, const CutGrid &coarse);
	// Cuts the cells that have a vertex (node >= 0), listed in active_.
	void cutActive(CutGrid &grid, int vertices);
	template<typename Weight, typename Graph>
	void cutWith(Graph &graph, CutGrid &grid, int vertices);

	int margin_ = 0;
	std::array<CutGrid, kMaxLevels + 1> coarse_; // [1..levels]; [0] unused (the caller's)
	std::vector<uint8_t> edge_, marks_;          // per coarse cell
	std::vector<int32_t> active_;                // vertex -> its cell, row-major
	std::array<size_t, kMaxLevels + 1> cellsCut_{};
	std::unique_ptr<Graphs> graphs_; // GCGraph's header stays out of this one
};

} // namespace depthkey
