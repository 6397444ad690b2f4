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
// confidence. Integer arithmetic only, and no division per pixel (issue 28:
// the divisions cost a third of the band's time): configure() tabulates the
// board and depth terms and turns the temporal term's divisor into a
// multiply (algo/exact_divisor.hpp), each giving what the divisions gave bit
// for bit. The two sums per pixel, the board distance and the colour
// change, come from vector rows over the span first
// (algo/evidence_terms_rows.hpp), the same values on every path. Tests
// compare it with the divisions it replaces (equal), with a double
// reference, and a row with fuse() of each pixel on every kernel path
// (tests/fused_evidence_test).
#pragma once

#include "algo/band_evidence.hpp"
#include "algo/board_model.hpp"
#include "algo/evidence_terms_rows.hpp"
#include "algo/exact_divisor.hpp"
#include "settings/settings.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

namespace depthkey {

class FusedEvidence final : public BandEvidence
{
public:
	// A hand writing on the board lies within the ToF noise of it, so depth
	// says board there as surely as on the board (-144 at the defaults),
	// more than the colour camera's whole capped say (+127): the hand was
	// lost wherever it touched the board (issue 29 section 6, seed 1 at
	// 14.2-16 s). Where colour and the board model together say lecturer by
	// kSureLecturerColour or more (SIOX clearly his, the pixel far from how
	// the board looks there) and the pixel's colour moved since the last
	// frame (by still_colour or more: a writing hand moves, the desk beside
	// him does not), depth's board verdict is held to kContactDepthFloor.
	// Measured (docs/accuracy.md, "The student's view in motion"): hand
	// recall 0.843 -> 0.976; without the motion condition 0.994, but the
	// desk, whose depth evidence is forced to "surely board" and whose
	// colours SIOX gives him, came back in (0.982 -> 0.942).
	static constexpr int kSureLecturerColour = 150, kContactDepthFloor = 100;
	// The hold also lasts through the still moments of writing (the chalk
	// held against the board: the colour the same from one frame to the
	// next) where the pixel was his in the last frame and its colour moved
	// within the last kHoldFrames frames. A desk never moves, so it is not
	// held; one his arm passed over is held for at most that long. Measured
	// (seed 1): the hand's worst frame 0.806 -> 0.99 (frames 360 and 385, a
	// still hand, lost without it); held wherever he was in the last frame,
	// however long still, the desk beside him came in and stayed (its worst
	// frame 0.965 -> 0.918).
	// Nor is a pixel held where depth saw him in front of the board (its
	// evidence above depth_pivot) within the last kHoldFrames frames: he
	// stood there and has walked off, and what he uncovered can look like
	// him (at 1920x1080, seed 1, frames 262-289, the light floor strip his
	// legs left, like his shirt, was held as a ghost: IoU 0.991 -> 0.951 at
	// frame 274; seed 1 0.974 -> 0.972). A hand on the board is within the
	// ToF noise of it, so depth never sees it in front. Measured with this:
	// the hand's worst frame 0.990, the 1080p ghosts gone (seed 1 0.975).
	static constexpr int kHoldFrames = 12; // about half a second at 25 fps

	FusedEvidence() { configure(DecisionSettings()); }
	// The weights' tables; boardMatch and stillColour >= 1.
	void configure(const DecisionSettings &settings);

	// The inputs of one frame; previous* may be null (first frame), and
	// are only read inside previousRoi.
	void bind(const RgbImage &colour, const Gray8Image &depthEvidence, SioxClassifier &classifier,
		  const BoardModel &board, const Gray8Image *previousAlpha, const RgbImage *previousColour,
		  const Roi &previousRoi);

	void confidences(int y, int x0, int x1, uint8_t *out) override;

	// The row kernels of the board distance, the colour change and the hold
	// (algo/evidence_terms_rows.hpp); the confidences are the same on every
	// path.
	void setKernelPath(KernelPath path)
	{
		boardDistance_ = boardDistanceRow(path);
		colourChange_ = colourChangeRow(path);
		stillHold_ = stillHoldRow(path);
	}

	// One pixel's confidence from its terms (the kernel, inlined in
	// confidences()): siox 1..255, depthEvidence 0..255, boardDistance -1 =
	// no model, previous alpha -1 = none, colourChange the L1 change since
	// then, movedLately: its colour moved (by still_colour or more) within
	// the last kHoldFrames frames and depth did not see him in front there
	// within them (stillHoldRow's flag). Divisions by powers of two are arithmetic
	// shifts (floor), the others truncate towards zero, each at most one
	// unit off the real value.
	uint8_t fuse(int siox, int depthEvidence, int boardDistance, int previousAlpha, int colourChange,
		     bool movedLately = false) const
	{
		const int colourAndBoard =
			siox - kConfidenceLecturer + boardTerm_[size_t(std::min(boardDistance, boardSaturates_) + 1)];
		int sum = colourAndBoard;
		if (previousAlpha >= 0 && colourChange < stillColour_)
			sum += temporalDivisor_.truncate(temporalWeight_ * (previousAlpha - 128) * (stillColour_ - colourChange));
		// Colour, the board model and the previous frame all come from the
		// colour camera and err together (a dark sleeve is dark in all
		// three): what they say together is capped at what one confidence
		// can say, and only then does the other camera's depth add.
		// Measured: uncapped, a saturated colour sum drowned depth (mean IoU /
		// BF of seeds 1-3 0.899 / 0.633 against 0.928 / 0.718 capped).
		sum = std::clamp(sum, 1 - int(kConfidenceLecturer), 255 - int(kConfidenceLecturer));
		const int depth = depthTerm_[uint8_t(depthEvidence)];
		const bool moved = previousAlpha >= 0 && colourChange >= stillColour_;
		const bool held = moved || (movedLately && previousAlpha >= 128);
		sum += colourAndBoard >= kSureLecturerColour && held ? std::max(depth, -kContactDepthFloor) : depth;
		return uint8_t(std::clamp(sum + int(kConfidenceLecturer), 1, 255));
	}

private:
	// The board term by distance + 1 (index 0: no model), constant from
	// 3 boardMatch on (at most 3 * 255); the depth term by evidence.
	std::array<int16_t, 3 * 255 + 2> boardTerm_{};
	int boardSaturates_ = 0;
	std::array<int16_t, 256> depthTerm_{};
	int temporalWeight_ = 0, stillColour_ = 1;
	ExactDivisor temporalDivisor_; // 128 stillColour
	const RgbImage *colour_ = nullptr;
	const Gray8Image *depthEvidence_ = nullptr;
	SioxClassifier *classifier_ = nullptr;
	const BoardModel *board_ = nullptr;
	const Gray8Image *previousAlpha_ = nullptr;
	const RgbImage *previousColour_ = nullptr;
	Roi previousRoi_;
	// A span's board distances and colour changes, from the row kernels;
	// sized to the colour width in bind() (once per size).
	std::vector<int16_t> distance_, change_;
	std::vector<uint8_t> held_; // the span's movedLately, from stillHold_
	// Per colour pixel, the frame (frame_, counted by bind()) its colour
	// last moved in, and the last frame depth saw him in front there; read
	// and written only where a previous frame is.
	// Stamps older than kStampRefresh frames are set to kStampRefresh * 2
	// old every kStampRefresh frames, so no age wraps past 65535.
	static constexpr uint16_t kStampRefresh = 16384;
	std::vector<uint16_t> lastMoved_, lastInFront_;
	int depthPivot_ = 144;
	uint16_t frame_ = 0;
	BoardDistanceFn boardDistance_ = boardDistanceRow(bestKernelPath());
	ColourChangeFn colourChange_ = colourChangeRow(bestKernelPath());
	StillHoldFn stillHold_ = stillHoldRow(bestKernelPath());
};

} // namespace depthkey
