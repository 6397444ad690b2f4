#include "algo/evidence_terms_rows.hpp"

#include <cstdlib>

namespace depthkey {

void boardDistanceRow_C(const Rgb8 *colour, const Rgba8 *model, const int gainQ8[3], int n, int16_t *distance)
{
	auto gained = [](int m, int g) { return (m * g + 128) >> 8; };
	for (int x = 0; x < n; ++x) {
		const Rgba8 m = model[x];
		const Rgb8 c = colour[x];
		distance[x] = m.a < kEvidenceLearnedVisits
				      ? int16_t(-1)
				      : int16_t(std::abs(c.r - gained(m.r, gainQ8[0])) + std::abs(c.g - gained(m.g, gainQ8[1])) +
						std::abs(c.b - gained(m.b, gainQ8[2])));
	}
}

void colourChangeRow_C(const Rgb8 *colour, const Rgb8 *previous, int n, int16_t *change)
{
	for (int x = 0; x < n; ++x)
		change[x] = int16_t(std::abs(colour[x].r - previous[x].r) + std::abs(colour[x].g - previous[x].g) +
				    std::abs(colour[x].b - previous[x].b));
}

BoardDistanceFn boardDistanceRow(KernelPath path)
{
	return sse2Rows(path) ? boardDistanceRow_SSE2 : path == KernelPath::Neon ? boardDistanceRow_NEON : boardDistanceRow_C;
}

ColourChangeFn colourChangeRow(KernelPath path)
{
	return sse2Rows(path) ? colourChangeRow_SSE2 : path == KernelPath::Neon ? colourChangeRow_NEON : colourChangeRow_C;
}

} // namespace depthkey
