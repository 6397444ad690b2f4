// The static scene's depth at every sample of a ray grid (what the lecturer
// is hidden behind, and the ground truth where nobody is), kept exactly but
// in about a byte a sample (issue 15: a float a sample was 1.2 MB at
// 640x480).
//
// Why a byte is enough: the depth is z of the plane a ray hits, and the
// rooms' planes mostly face the camera: the whole board and wall are one
// value, the desk's top one value a row or a few hundred. So each row keeps
// the distinct floats it has (compared bit for bit) and a byte a sample
// pointing at one; a row with more than 256 (a tilted calibration target
// seen close, the ToF's rotated view of the board) keeps its floats whole.
// Rows are read back whole, one at a time: the grid reads them in order.
#pragma once

#include <cstdint>
#include <vector>

namespace depthkey::sim {

class StaticDepth
{
public:
	// z: width x height floats, row-major.
	void assign(int width, int height, const std::vector<float> &z);
	// Row j's floats, as they were; valid until row() is asked for another
	// row or assign() is called.
	const float *row(int j) const;

private:
	struct Row {
		uint32_t values = 0;  // offset into values_: the palette, or the whole row
		uint32_t indices = 0; // offset into indices_ (palette rows)
		bool whole = false;
	};
	int width_ = 0;
	std::vector<Row> rows_;
	std::vector<float> values_;
	std::vector<uint8_t> indices_;
	// The row last read back.
	mutable std::vector<float> decoded_;
	mutable int decodedRow_ = -1;
};

} // namespace depthkey::sim
