// SIOX on the undecided band of a trimap, then its post-processing, then the
// soft alpha. Only band pixels are ever computed or changed, so the seeds are
// never contradicted (surely lecturer stays 255, surely board stays 0) and
// the cost follows the band's size, not the image's:
//   1. classify: each band pixel gets its confidence from the evidence
//      (algo/band_evidence.hpp: SIOX's cached colour decision, or that fused
//      with the board model, depth and the previous frame);
//   2. smoothing: `smoothing` passes of a 3x3 box average of the confidence
//      (as SIOX's smoothcm with weights 1/3), then a threshold at one half;
//      or, when a graph cut is set (the keyer's), the minimum cut of
//      algo/band_graph_cut.hpp instead;
//   3. components: keep every 4-connected lecturer region of the band that
//      touches a surely-lecturer pixel (not only the largest: a hand behind a
//      thin undecided wrist stays), or the image border when the lecturer
//      goes on beyond it, or is large: at least 1/kFreeComponentDivisor of
//      the image and kFreeComponentMinPx (400 pixels at 640x480: an arm cut
//      from the body by a vest of the board's colour); drop the rest
//      (specks, chalk writing);
//   4. holes: a board region of the band that reaches no surely-board pixel
//      and not the image border is enclosed by the lecturer: fill it, except
//      where the evidence says board clearly (confidence below
//      kClearlyBoard: the board seen between an arm and the body);
//   5. soft alpha: band pixels on the final boundary take their colour's
//      confidence (the distance ratio), kept on the side of the decision so
//      that thresholding the alpha at 128 gives back the mask.
//
// The band is kept as a list of horizontal spans (row, first, last), found
// once per frame (algo/band_scan.hpp skips the seeds between them, 16 labels
// at a time on the SIMD paths); every later step walks the spans. The working mask has a
// one-pixel frame of kBandOutside around the image, so neighbours are read
// without bounds checks and no pixel index is ever divided back into x, y.
#pragma once

#include "algo/band_components.hpp"
#include "algo/band_evidence.hpp"
#include "algo/band_graph_cut.hpp"
#include "algo/image.hpp"
#include "algo/kernel_path.hpp"
#include "algo/siox_classifier.hpp"
#include "algo/trimap.hpp"
#include "settings/settings.hpp"

#include <cstdint>
#include <vector>

namespace depthkey {

class SioxRefiner
{
public:
	static constexpr size_t kFreeComponentDivisor = 768, kFreeComponentMinPx = 400;
	// A hole pixel whose confidence is below this stays board: a quarter of
	// the way from board's end of the scale to the decision threshold.
	static constexpr uint8_t kClearlyBoard = 32;

	void configure(const SioxSettings &settings) { settings_ = settings; }
	// For the next refine(): the lecturer goes on beyond the image border
	// (SeedMapper::lecturerBeyondBorder), so band regions SIOX calls
	// lecturer that touch the border are his too, seed or no seed.
	void setLecturerBeyondBorder(bool beyond) { lecturerBeyondBorder_ = beyond; }
	// The band decided by a minimum cut instead of smoothing (smoothness 0
	// = off), in frames whose band has at most maxBandPixels pixels.
	void setGraphCut(int smoothness, int edgeSigma, size_t maxBandPixels, int levels = 0, int margin = 0)
	{
		cut_.configure(smoothness, edgeSigma);
		cut_.setLevels(levels, margin);
		cutMaxBandPixels_ = maxBandPixels;
	}
	// The band scan's row kernel (algo/band_scan.hpp); the best by default.
	void setKernelPath(KernelPath path) { kernelPath_ = path; }

	// roi must contain every non-board trimap pixel with one pixel to spare
	// (or the image border). alpha is resized to the image and written
	// everywhere: 0 outside the ROI.
	void refine(const RgbImage &colour, const Gray8Image &trimap, const Roi &roi, BandEvidence &evidence,
		    Gray8Image &alpha);
	// SIOX's colour decision alone (ColourEvidence).
	void refine(const RgbImage &colour, const Gray8Image &trimap, const Roi &roi, SioxClassifier &classifier,
		    Gray8Image &alpha)
	{
		ColourEvidence evidence(classifier, colour);
		refine(colour, trimap, roi, evidence, alpha);
	}

	// The band pixels of the last refine(), for previews and tests.
	size_t bandPixels() const { return bandPixels_; }

private:
	using Span = BandSpan; // pixels [x0, x1) of row y, from index first in the band arrays

	void collectAndClassify(const Gray8Image &trimap, const Roi &roi, BandEvidence &evidence);
	void smooth();
	void decideByCut(const RgbImage &colour, const Gray8Image &trimap);
	void writeAlpha(const Roi &roi, Gray8Image &alpha) const;

	// Index of image pixel (x, y) in work_.
	int at(int x, int y) const { return (y + 1) * stride_ + x + 1; }
	// Calls f(index in work_, index in the band arrays) for every band pixel.
	template<typename F>
	void forEachBandPixel(F f) const
	{
		for (const Span &s : spans_)
			for (int x = s.x0, p = at(s.x0, s.y), k = s.first; x < s.x1; ++x, ++p, ++k)
				f(p, k);
	}

	SioxSettings settings_;
	bool lecturerBeyondBorder_ = false;
	KernelPath kernelPath_ = bestKernelPath();
	int width_ = 0, height_ = 0, stride_ = 0;
	Gray8Image work_;             // (w+2) x (h+2): seeds, band pixels 0 / 255, kBandOutside around
	std::vector<Span> spans_;
	BandGraphCut cut_;
	size_t cutMaxBandPixels_ = 0;
	size_t bandPixels_ = 0;
	std::vector<uint8_t> colourConfidence_, next_;
	BandComponents components_; // steps 3 and 4
};

} // namespace depthkey
