#include "algo/quantised_colour.hpp"

namespace depthkey {

QuantisedLabTable::QuantisedLabTable(Fill fill)
	: lab_(new Lab16[kQuantisedColours]), known_(kQuantisedColours / 64, 0)
{
	if (fill == Fill::OnDemand)
		return;
	for (uint32_t i = 0; i < kQuantisedColours; ++i)
		this->fill(i);
}

void QuantisedLabTable::fill(uint32_t index) const
{
	Rgb8 c = quantisedCentre(index);
	lab_[index] = converter_.convert(c.r, c.g, c.b);
	known_[index >> 6] |= uint64_t(1) << (index & 63);
}

} // namespace depthkey
