// Colour learning (paper 6.1-6.2): lecturer colours from the surely-lecturer
// seeds, board colours from well outside the superset, on a sparse grid of
// about `samples` points per frame (jittered from frame to frame, so every
// pixel is visited over time). Both go into decaying histograms: the board
// learns fast (its content changes all the time), the lecturer slowly.
//
// The signatures are derived once `initial_frames` frames are in, and after
// that re-derived only when the samples have changed enough: when the share
// of samples the current signatures put in the wrong class has risen by
// `relearn_misfit` above what it was right after the last derivation.
#pragma once

#include "algo/decaying_histogram.hpp"
#include "algo/image.hpp"
#include "algo/siox_classifier.hpp"
#include "config/settings.hpp"

#include <vector>

namespace depthkey {

// Builds both signatures from the histograms and resets the decision cache.
// points is work space with room for kQuantisedColours.
void deriveSignatures(const DecayingHistogram &lecturer, const DecayingHistogram &board,
		      const QuantisedLabTable &lab, std::vector<WeightedLab> &points,
		      SioxClassifier &classifier);

class ColourLearner
{
public:
	explicit ColourLearner(const QuantisedLabTable &lab);

	void configure(const LearningSettings &settings);
	void reset();

	// trimap at colour resolution, learnBoard at ToF resolution. Returns
	// true when the signatures were re-derived.
	bool learn(const RgbImage &colour, const Gray8Image &trimap, const Gray8Image &learnBoard,
		   SioxClassifier &classifier);

	int frames() const { return frames_; }
	int derivations() const { return derivations_; }
	double misfitRate() const { return misfit_; }

private:
	const QuantisedLabTable &lab_;
	LearningSettings settings_;
	DecayingHistogram lecturer_, board_;
	std::vector<WeightedLab> points_;
	int frames_ = 0;
	int derivations_ = 0;
	double misfit_ = 0.0;     // smoothed share of misclassified samples
	double baseline_ = -1.0;  // misfit_ right after the last derivation
};

} // namespace depthkey
