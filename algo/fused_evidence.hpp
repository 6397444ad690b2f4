// The decision inside the superset (issue 11 section 4): per pixel, one
// confidence from all the evidence, each term in units of SIOX's colour
// confidence (1..255 around kConfidenceLecturer = 128):
//   colour    SIOX's distance ratio to the two signatures, c - 128;
//   depth     the depth evidence e (DepthSeeder::depthEvidence: the
//             log-likelihood ratio of the pixel's depth between the
//             lecturer's surface and the board, given the ToF noise there,
//             mapped into the colour image and blended between the depth
//             frames around the colour frame);
//               depth_weight * (e - depth_pivot) / 64
//             (clean depth saturates e at 254 or 1, +-110 at the defaults:
//             about as much as the clearest colour, so where depth is clean
//             and colour is ambiguous, depth wins; a noisy or mixed depth
//             says little, and colour decides);
//   board     the board model at the pixel's own place (algo/board_model.hpp)
//             within board_match: -board_weight * (match - d) / match, for
//             the L1 distance d;
//   temporal  the previous frame's alpha a', where the pixel's colour changed
//             by less than still_colour (Δ):
//               temporal_weight * (a' - 128) / 128 * (still - Δ) / still.
// The colour camera's terms (colour, board, temporal) are summed and capped
// at +-127 first, then depth adds; that + 128, clamped to 1..255, is the
// confidence. Integer arithmetic
// only; tests compare it with a double reference (tests/fused_evidence_test).
#pragma once

#include "algo/band_evidence.hpp"
#include "algo/board_model.hpp"
#include "settings/settings.hpp"

namespace depthkey {

class FusedEvidence final : public BandEvidence
{
public:
	void configure(const DecisionSettings &settings) { settings_ = settings; }

	// The inputs of one frame; previous* may be null (first frame), and
	// are only read inside previousRoi.
	void bind(const RgbImage &colour, const Gray8Image &depthEvidence, SioxClassifier &classifier,
		  const BoardModel &board, const Gray8Image *previousAlpha, const RgbImage *previousColour,
		  const Roi &previousRoi);

	void confidences(int y, int x0, int x1, uint8_t *out) override;

	// One pixel's confidence from its terms (the kernel, for tests):
	// siox 1..255, depthEvidence 0..255, boardDistance -1 = no model, previous
	// alpha -1 = none, colourChange the L1 change since then.
	static uint8_t fuse(const DecisionSettings &s, int siox, int depthEvidence, int boardDistance, int previousAlpha,
			    int colourChange);

private:
	DecisionSettings settings_;
	const RgbImage *colour_ = nullptr;
	const Gray8Image *depthEvidence_ = nullptr;
	SioxClassifier *classifier_ = nullptr;
	const BoardModel *board_ = nullptr;
	const Gray8Image *previousAlpha_ = nullptr;
	const RgbImage *previousColour_ = nullptr;
	Roi previousRoi_;
};

} // namespace depthkey
