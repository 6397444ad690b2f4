// A per-sample table of 32-bit values (floats, packed colours) that has few
// distinct values a row, kept exactly in about a byte a sample (issue 15):
// each row keeps the distinct values it has (compared bit for bit) and a
// byte a sample pointing at one; a row with more than 256 keeps its values
// whole. Rows are read back whole, one at a time, as the simulator reads
// its tables: in order.
//
// The simulator's tables are like that because its static scene is a few
// planes, most of them facing the camera: the board and wall are one depth,
// the desk's top one a row; a row of the colour camera shows the wall, the
// board's few slide colours and inks, the desk. Rows with more (a tilted
// calibration target seen close, the ToF's rotated view) cost what a plain
// table would.
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>
#include <vector>

namespace depthkey::sim {

template<typename T>
class RowPalette
{
	static_assert(sizeof(T) == sizeof(uint32_t), "values are compared as 32-bit patterns");

public:
	// Starts a table of width x height; then appendRow() height times.
	void begin(int width, int height)
	{
		width_ = width;
		rows_.clear();
		rows_.reserve(height);
		values_.clear();
		indices_.clear();
		decoded_.assign(width, T{});
		decodedRow_ = -1;
	}

	void appendRow(const T *in)
	{
		palette_.assign(width_, 0);
		for (int i = 0; i < width_; ++i)
			palette_[i] = std::bit_cast<uint32_t>(in[i]);
		std::sort(palette_.begin(), palette_.end());
		palette_.erase(std::unique(palette_.begin(), palette_.end()), palette_.end());
		Row row;
		row.values = static_cast<uint32_t>(values_.size());
		row.whole = palette_.size() > 256;
		if (row.whole) {
			values_.insert(values_.end(), in, in + width_);
		} else {
			for (uint32_t bits : palette_)
				values_.push_back(std::bit_cast<T>(bits));
			row.indices = static_cast<uint32_t>(indices_.size());
			for (int i = 0; i < width_; ++i) {
				auto at = std::lower_bound(palette_.begin(), palette_.end(), std::bit_cast<uint32_t>(in[i]));
				indices_.push_back(static_cast<uint8_t>(at - palette_.begin()));
			}
		}
		rows_.push_back(row);
	}

	// After the last row: the tables at their size (grown by push_back they
	// could hold up to twice their bytes), no scratch kept.
	void finish()
	{
		values_.shrink_to_fit();
		indices_.shrink_to_fit();
		palette_ = {};
	}

	void assign(int width, int height, const std::vector<T> &table)
	{
		begin(width, height);
		for (int j = 0; j < height; ++j)
			appendRow(table.data() + static_cast<size_t>(j) * width);
		finish();
	}

	int height() const { return static_cast<int>(rows_.size()); }

	// Row j's values, as they were; valid until row() is asked for another
	// row or the table is rebuilt.
	const T *row(int j) const
	{
		const Row &row = rows_[j];
		if (row.whole)
			return values_.data() + row.values;
		if (j != decodedRow_) {
			const T *palette = values_.data() + row.values;
			const uint8_t *index = indices_.data() + row.indices;
			for (int i = 0; i < width_; ++i)
				decoded_[i] = palette[index[i]];
			decodedRow_ = j;
		}
		return decoded_.data();
	}

private:
	struct Row {
		uint32_t values = 0;  // offset into values_: the palette, or the whole row
		uint32_t indices = 0; // offset into indices_ (palette rows)
		bool whole = false;
	};
	int width_ = 0;
	std::vector<Row> rows_;
	std::vector<T> values_;
	std::vector<uint8_t> indices_;
	std::vector<uint32_t> palette_; // appendRow()'s scratch
	// The row last read back.
	mutable std::vector<T> decoded_;
	mutable int decodedRow_ = -1;
};

} // namespace depthkey::sim
