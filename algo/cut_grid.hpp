// One level of the band's cut energy on a grid (algo/coarse_to_fine_cut.hpp).
// A cell is free (the cut decides it) or fixed (a seed, or outside the band).
// Fixed neighbours are already folded into a free cell's unary term, and
// flagged in `touches`, so a level holds only free cells and the links
// between them:
//   E = sum_free unary(label) + sum_{free p~q, cut} link(p, q)
// with unary[c] = cost(board) - cost(lecturer) (> 0 leans lecturer) and
// right[c], down[c] the weights of the links to the free cell right of and
// below c (0 where there is none, so a non-zero link always leads to a free
// cell of the same row or column). Only `state` says which cells are free:
// every other array is valid at free cells only, so a frame clears one byte
// a cell, not seventeen.
#pragma once

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

namespace depthkey {

struct CutGrid {
	static constexpr uint8_t kFixed = 0, kFree = 1;
	static constexpr uint8_t kTouchesLecturer = 1, kTouchesBoard = 2;
	// A link inside a 2x2 block of the finest grid that its builder left to
	// be weighed on demand (CoarseToFineCut::DeferredLinks): coarser levels
	// never read it, and the finest level cuts only a few blocks.
	static constexpr int32_t kLinkDeferred = -1;

	int width = 0, height = 0;
	std::vector<uint8_t> state;    // kFixed / kFree
	std::vector<int32_t> unary;    // toLecturer - toBoard, fixed neighbours included
	std::vector<int32_t> right;    // link to the free cell at +1, else 0
	std::vector<int32_t> down;     // link to the free cell at +width, else 0
	std::vector<uint8_t> touches;  // kTouchesLecturer | kTouchesBoard: fixed neighbours' sides
	std::vector<uint8_t> label;    // after solving: 1 lecturer, 0 board
	std::vector<int32_t> node;     // graph vertex while being solved, else -1

	// Sizes the level; the vectors only ever grow (no allocation in a steady
	// state), and every cell is left fixed.
	void reset(int w, int h)
	{
		width = w;
		height = h;
		const size_t n = size_t(w) * size_t(h);
		for (auto *v : { &state, &touches, &label })
			if (v->size() < n)
				v->resize(n);
		for (auto *v : { &unary, &right, &down, &node })
			if (v->size() < n)
				v->resize(n);
		std::fill(state.begin(), state.begin() + std::ptrdiff_t(n), kFixed);
	}
	size_t cells() const { return size_t(width) * size_t(height); }

	// The next run of free cells of row y at or after x: [x0, x1), x0 ==
	// width when there is none. Most of a level's bounding box is fixed (the
	// core, the board beyond the band), so the fixed cells are skipped eight
	// at a time instead of walked; and a run of free cells (the band's rows
	// are tens of cells wide) is measured eight at a time too.
	struct Run {
		int x0, x1;
	};
	Run nextRun(int y, int x) const
	{
		const uint8_t *row = state.data() + size_t(y) * size_t(width);
		if constexpr (std::endian::native == std::endian::little)
			for (uint64_t word; x + 8 <= width; x += 8) {
				std::memcpy(&word, row + x, 8);
				if (word) {
					x += std::countr_zero(word) / 8; // kFixed is 0
					break;
				}
			}
		while (x < width && row[x] == kFixed)
			++x;
		int end = x;
		if constexpr (std::endian::native == std::endian::little)
			for (uint64_t word; end + 8 <= width; end += 8) {
				std::memcpy(&word, row + end, 8);
				// A byte that is not kFree (1) leaves a bit standing.
				if (const uint64_t other = word ^ 0x0101010101010101u) {
					end += std::countr_zero(other) / 8;
					break;
				}
			}
		while (end < width && row[end] == kFree)
			++end;
		return { x, end };
	}
};

} // namespace depthkey
