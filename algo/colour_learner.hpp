// Colour learning (paper 6.1-6.2): lecturer colours from the depth subset
// (trimap labels >= kTrimapSubset), board colours from well outside the superset, on a sparse grid of
// about `samples` points per frame (jittered from frame to frame, so every
// pixel is visited over time). Both go into decaying histograms: the board
// learns fast (its content changes all the time), the lecturer slowly.
//
// While the first `initial_frames` frames come in, the signatures are
// derived from what is there every frame (provisional: few samples yet, but
// SIOX on them beats the raw depth superset); after that they are re-derived
// only when the samples have changed enough: when the share of samples the
// current signatures put in the wrong class has risen by `relearn_misfit`
// above what it was right after the last derivation.
#pragma once

#include "algo/decaying_histogram.hpp"
#include "algo/image.hpp"
#include "algo/siox_classifier.hpp"
#include "settings/settings.hpp"

#include <memory>
#include <vector>

namespace depthkey {

// Work space of deriveSignatures, sized once.
struct SignatureScratch {
	SignatureScratch();
	// Room for kQuantisedColours, left uninitialised: only as many points
	// as a histogram has non-empty cells are written, and the pages past
	// them are never touched (3 MB that depthkey-siox would zero for nothing).
	std::unique_ptr<WeightedLab[]> points;
	std::vector<uint64_t> lecturerCells, boardCells; // coarse colour densities
};

// Builds both signatures from the histograms and resets the decision cache.
// A colour more frequent in the other class's samples is left out of a
// class's signature: it came from the seeds' errors.
void deriveSignatures(const DecayingHistogram &lecturer, const DecayingHistogram &board,
		      const QuantisedLab &lab, SignatureScratch &scratch, SioxClassifier &classifier);

class ColourLearner
{
public:
	explicit ColourLearner(const QuantisedLab &lab);

	void configure(const LearningSettings &settings);
	void reset();

	// Board colours are taken only from surely-board pixels of the trimap
	// (colour resolution) with no other label within marginPx colour pixels
	// in any of 8 directions, so a late depth frame or light scattered onto
	// the board cannot teach the lecturer's colours as board. Judged in the
	// colour image itself: the depth camera's view differs (wider lens,
	// parallax), so a ToF-resolution mask cannot be looked up by scaling.
	// Returns true when the signatures were re-derived.
	bool learn(const RgbImage &colour, const Gray8Image &trimap, int marginPx, SioxClassifier &classifier);

	int frames() const { return frames_; }
	// Still within the first initial_frames frames.
	bool learning() const { return frames_ < settings_.initialFrames; }
	int derivations() const { return derivations_; }
	double misfitRate() const { return misfit_; }

private:
	const QuantisedLab &lab_;
	LearningSettings settings_;
	DecayingHistogram lecturer_, board_;
	SignatureScratch scratch_;
	int frames_ = 0;
	int derivations_ = 0;
	double misfit_ = 0.0;     // smoothed share of misclassified samples
	double baseline_ = -1.0;  // misfit_ right after the last derivation
};

} // namespace depthkey
