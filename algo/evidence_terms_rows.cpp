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

void stillHoldRow_C(const int16_t *change, const uint8_t *evidence, int n, const StillHold &h, uint16_t *moved,
		    uint16_t *inFront, uint8_t *held)
{
	for (int x = 0; x < n; ++x) {
		if (change[x] >= h.still)
			moved[x] = h.frame;
		if (evidence[x] > h.pivot)
			inFront[x] = h.frame;
		held[x] = uint16_t(h.frame - moved[x]) < h.holdFrames && uint16_t(h.frame - inFront[x]) >= h.holdFrames;
	}
}

BoardDistanceFn boardDistanceRow(KernelPath path)
{
	return sse2Rows(path) ? boardDistanceRow_SSE2 : path == KernelPath::Neon ? boardDistanceRow_NEON : boardDistanceRow_C;
}

ColourChangeFn colourChangeRow(KernelPath path)
{
	return sse2Rows(path) ? colourChangeRow_SSE2 : path == KernelPath::Neon ? colourChangeRow_NEON : colourChangeRow_C;
}

StillHoldFn stillHoldRow(KernelPath path)
{
	return sse2Rows(path) ? stillHoldRow_SSE2 : path == KernelPath::Neon ? stillHoldRow_NEON : stillHoldRow_C;
}

} // namespace depthkey
