// SIOX's per-colour decision, cached: a colour is lecturer when its squared
// distance to the nearest lecturer centroid is not larger than to the nearest
// board centroid (SIOX 1.13: background iff minBg < minFg).
//
// The cache holds, per quantised colour, a confidence 1..255 (0 = not yet
// computed): round-up of 1 + 254 * dBg / (dBg + dFg) with d the Euclidean
// distances (not squared), forced to >= 128 exactly when the colour is
// lecturer and to <= 127 otherwise. It is SIOX's detail refinement (alpha
// from the ratio of the distances to the two signatures) made symmetric, and
// doubles as the soft alpha on the boundary. A pixel costs one lookup; a
// colour seen for the first time since the signatures changed costs two k-d
// tree searches.
#pragma once

#include "algo/colour_signature.hpp"
#include "algo/quantised_colour.hpp"

#include <cstdint>
#include <vector>

namespace depthkey {

constexpr uint8_t kConfidenceLecturer = 128; // confidence >= this: lecturer

class SioxClassifier
{
public:
	explicit SioxClassifier(const QuantisedLab &lab);

	ColourSignature &lecturer() { return lecturer_; }
	ColourSignature &board() { return board_; }
	const ColourSignature &lecturer() const { return lecturer_; }
	const ColourSignature &board() const { return board_; }

	// Call after changing a signature: forgets every cached decision.
	void signaturesChanged();
	// SIOX cannot decide without a board signature; with no lecturer
	// signature every colour is board (the reference refuses to run).
	bool ready() const { return !board_.empty(); }

	uint8_t confidence(uint32_t quantised)
	{
		uint8_t c = cache_[quantised];
		return c ? c : decide(quantised);
	}

	// The uncached decision for a Lab colour (tests, and the cache filler).
	uint8_t decideLab(Lab16 lab) const;

private:
	uint8_t decide(uint32_t quantised);

	const QuantisedLab &lab_;
	ColourSignature lecturer_, board_;
	std::vector<uint8_t> cache_;
};

// Integer square root, floor(sqrt(v)).
uint32_t integerSqrt(uint32_t v);

} // namespace depthkey
