// Colours quantised to 6 bits per channel (262144 cells of 4x4x4 code
// values): the key of the colour histograms and of SIOX's decision cache, so
// that classifying a pixel is one shift-and-or and one table lookup. A cell
// is about 1.5 L* units wide, finer than the sensor noise of a webcam.
#pragma once

#include "algo/image.hpp"
#include "algo/lab_converter.hpp"

#include <cstdint>
#include <memory>
#include <vector>

namespace depthkey {

constexpr int kQuantBits = 6;
constexpr uint32_t kQuantisedColours = 1u << (3 * kQuantBits);

inline uint32_t quantiseColour(Rgb8 c)
{
	return (uint32_t(c.r >> 2) << 12) | (uint32_t(c.g >> 2) << 6) | uint32_t(c.b >> 2);
}

// The colour at the middle of a cell (code values 4q .. 4q+3 -> 4q+2).
inline Rgb8 quantisedCentre(uint32_t index)
{
	return { uint8_t(((index >> 12) & 63) * 4 + 2), uint8_t(((index >> 6) & 63) * 4 + 2),
		 uint8_t((index & 63) * 4 + 2) };
}

// Lab16 of every cell centre (1.5 MB) so that signatures and the decision
// cache never convert colours per frame. Only the colours of the cells
// looked up are ever needed (a histogram's non-empty cells, a decision
// cache miss), never a pixel's own lookup.
class QuantisedLabTable
{
public:
	// Eager: every cell at construction (about 5 ms): the daemon, whose
	// table is read by more than one stage and must never change after.
	// OnDemand: a cell the first time it is asked for: depthkey-siox, which
	// looks up the few thousand colours of one photo and would otherwise
	// spend longer building the table than segmenting (issue 15). One
	// thread only: a lookup may write the cell.
	enum class Fill { Eager, OnDemand };
	explicit QuantisedLabTable(Fill fill = Fill::Eager);

	const Lab16 &operator[](uint32_t index) const
	{
		if (!((known_[index >> 6] >> (index & 63)) & 1)) [[unlikely]]
			fill(index);
		return lab_[index];
	}

private:
	void fill(uint32_t index) const;

	LabConverter converter_;
	// Left uninitialised: pages of cells never filled are never touched.
	std::unique_ptr<Lab16[]> lab_;
	mutable std::vector<uint64_t> known_; // a bit a cell: lab_ holds it
};

} // namespace depthkey
