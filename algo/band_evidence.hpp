// What decides the undecided pixels of a trimap: a confidence per pixel,
// 1..255, lecturer when >= kConfidenceLecturer (algo/siox_classifier.hpp).
// SioxRefiner asks for it span by span (a run of band pixels in one row),
// so the call is virtual per span, not per pixel.
//   ColourEvidence  SIOX's colour decision alone (still images, depthkey-siox);
//   FusedEvidence   colour, the per-pixel board model, the graded depth
//                   trimap and the previous frame (algo/fused_evidence.hpp).
#pragma once

#include "algo/image.hpp"
#include "algo/quantised_colour.hpp"
#include "algo/siox_classifier.hpp"

#include <cstdint>

namespace depthkey {

class BandEvidence
{
public:
	virtual ~BandEvidence() = default;
	// Confidences of pixels [x0, x1) of row y into out[0 .. x1 - x0).
	virtual void confidences(int y, int x0, int x1, uint8_t *out) = 0;
};

class ColourEvidence final : public BandEvidence
{
public:
	ColourEvidence(SioxClassifier &classifier, const RgbImage &colour) : classifier_(classifier), colour_(colour) {}
	void confidences(int y, int x0, int x1, uint8_t *out) override
	{
		const Rgb8 *c = colour_.row(y);
		for (int x = x0; x < x1; ++x)
			*out++ = classifier_.confidence(quantiseColour(c[x]));
	}

private:
	SioxClassifier &classifier_;
	const RgbImage &colour_;
};

} // namespace depthkey
