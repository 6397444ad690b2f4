// SIOX on one still image with a trimap (GIMP's foreground select, and
// depthkey-siox): every surely-lecturer pixel is a lecturer sample, every
// surely-board pixel a board sample (the reference's "known" pixels), then
// the same classification, post-processing and soft alpha as the pipeline.
// A StillSiox is for one thread (its decision cache fills as it goes).
#pragma once

#include "algo/colour_learner.hpp"
#include "algo/decaying_histogram.hpp"
#include "algo/siox_classifier.hpp"
#include "algo/siox_refiner.hpp"

namespace depthkey {

class StillSiox
{
public:
	StillSiox();

	void configure(const SioxSettings &settings) { refiner_.configure(settings); }

	// trimap: 0 board, 255 lecturer, other undecided; same size as colour.
	// alpha receives 0..255, mask 0 / 255 (alpha >= 128). Returns -EINVAL
	// when the sizes differ, -ENODATA when the trimap has no board pixel
	// (SIOX cannot decide without a board signature).
	int segment(const RgbImage &colour, const Gray8Image &trimap, Gray8Image &mask, Gray8Image &alpha);

	const SioxClassifier &classifier() const { return classifier_; }

private:
	QuantisedLab lab_;
	SioxClassifier classifier_;
	SioxRefiner refiner_;
	DecayingHistogram lecturer_, board_;
	SignatureScratch scratch_;
};

} // namespace depthkey
