// Box sums over a window of (2r + 1) x (2r + 1) pixels that follow an edge
// (issue 28): per column, sums over the window's rows, kept only for the
// columns asked for, and their sum over the window's columns slid along a
// run of pixels. The guided filter and the boundary unmixing compute only
// near the decided edge, about a quarter of the ROI, with them. Sums are
// modulo 2^32 (a box sum of the callers' values is below 2^32, so sums of
// differences of wrapped sums are exact).
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>

namespace depthkey {

// Per column, the sums of K values over the rows [y - r, y + r] clipped to
// [0, h) of some row y, modulo 2^32; rows[x] is that y. Brought to row y
// from y - 1 by a row in and a row out, from anything else afresh.
template<size_t K>
struct ColumnSums {
	std::array<uint32_t *, K> sums;
	int *rows;

	// values(row, x) gives the K values of a pixel.
	template<class Values>
	void bring(int x, int y, int r, int h, const Values &values)
	{
		if (rows[x] == y)
			return;
		auto add = [&](int row, uint32_t sign) {
			const std::array<uint32_t, K> v = values(row, x);
			for (size_t k = 0; k < K; ++k)
				sums[k][x] += sign * v[k];
		};
		if (rows[x] == y - 1) {
			if (y + r < h)
				add(y + r, 1u);
			if (y - r - 1 >= 0)
				add(y - r - 1, ~0u); // minus, modulo 2^32
		} else {
			for (size_t k = 0; k < K; ++k)
				sums[k][x] = 0;
			for (int row = std::max(0, y - r); row < std::min(h, y + r + 1); ++row)
				add(row, 1u);
		}
		rows[x] = y;
	}

	// Columns [x0, x1) to row y, as bring() each: a run of columns that
	// held row y - 1 moves down at once, step(s, e) adding row y + r's
	// values to columns [s, e) and taking off row y - r - 1's (a vector row,
	// algo/column_sums_rows.hpp); any other column one at a time.
	template<class Values, class Step>
	void bringRun(int x0, int x1, int y, int r, int h, const Values &values, const Step &step)
	{
		for (int x = x0; x < x1;) {
			if (rows[x] != y - 1) {
				bring(x, y, r, h, values);
				++x;
				continue;
			}
			int e = x + 1;
			while (e < x1 && rows[e] == y - 1)
				++e;
			step(x, e);
			std::fill(rows + x, rows + e, y);
			x = e;
		}
	}
};

// The sums of K column sums over a window of columns [x - r, x + r]
// clipped to [0, w), slid one column at a time, modulo 2^32.
template<size_t K>
struct SlidingSums {
	std::array<const uint32_t *, K> columns;
	std::array<uint32_t, K> sums{};

	void add(int x, uint32_t sign)
	{
		for (size_t k = 0; k < K; ++k)
			sums[k] += sign * columns[k][x];
	}
	// The window of x = s - 1: columns [s - 1 - r, s + r).
	void start(int s, int r, int w)
	{
		for (int x = std::max(0, s - 1 - r); x < std::min(w, s + r); ++x)
			add(x, 1u);
	}
	// The window of x from that of x - 1.
	void advance(int x, int r, int w)
	{
		if (x + r < w)
			add(x + r, 1u);
		if (x - r - 1 >= 0)
			add(x - r - 1, ~0u);
	}
};

} // namespace depthkey
