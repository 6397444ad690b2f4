#include "algo/quantised_colour.hpp"

namespace depthkey {

QuantisedLabTable::QuantisedLabTable() : lab_(kQuantisedColours)
{
	LabConverter converter;
	for (uint32_t i = 0; i < kQuantisedColours; ++i) {
		Rgb8 c = quantisedCentre(i);
		lab_[i] = converter.convert(c.r, c.g, c.b);
	}
}

} // namespace depthkey
