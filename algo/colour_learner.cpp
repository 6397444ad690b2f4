#include "algo/colour_learner.hpp"

#include "algo/trimap.hpp"

#include <algorithm>
#include <cmath>

namespace depthkey {

namespace {

// The misfit share is smoothed over a few frames so that one odd frame (a
// flash, a late depth frame) does not trigger a re-derivation.
constexpr double kMisfitSmoothing = 0.2;

} // namespace

void deriveSignatures(const DecayingHistogram &lecturer, const DecayingHistogram &board,
		      const QuantisedLabTable &lab, std::vector<WeightedLab> &points,
		      SioxClassifier &classifier)
{
	points.resize(kQuantisedColours);
	size_t n = lecturer.collect(lab, points.data());
	classifier.lecturer().build(points.data(), n);
	n = board.collect(lab, points.data());
	classifier.board().build(points.data(), n);
	classifier.signaturesChanged();
}

ColourLearner::ColourLearner(const QuantisedLabTable &lab) : lab_(lab), points_(kQuantisedColours)
{
}

void ColourLearner::configure(const LearningSettings &settings)
{
	if (settings == settings_ && frames_ > 0)
		return;
	settings_ = settings;
	lecturer_.setRate(settings.lecturerRate);
	board_.setRate(settings.boardRate);
	reset();
}

void ColourLearner::reset()
{
	lecturer_.clear();
	board_.clear();
	frames_ = 0;
	derivations_ = 0;
	misfit_ = 0.0;
	baseline_ = -1.0;
}

bool ColourLearner::learn(const RgbImage &colour, const Gray8Image &trimap, const Gray8Image &learnBoard,
			  SioxClassifier &classifier)
{
	const int w = colour.width(), h = colour.height();
	const int tw = learnBoard.width(), th = learnBoard.height();
	if (trimap.width() != w || trimap.height() != h || tw == 0 || th == 0)
		return false;
	int step = std::max(1, static_cast<int>(std::sqrt(double(w) * h / settings_.samples)));
	int offset = (frames_ * 7) % step; // jitter: a different sub-grid each frame
	bool judge = classifier.ready() && derivations_ > 0;
	unsigned samples = 0, misfits = 0;
	for (int y = offset; y < h; y += step) {
		const Rgb8 *c = colour.row(y);
		const uint8_t *t = trimap.row(y);
		const uint8_t *learn = learnBoard.row(y * th / h);
		for (int x = offset; x < w; x += step) {
			bool isLecturer = t[x] == kTrimapLecturer;
			if (!isLecturer && !learn[x * tw / w])
				continue;
			uint32_t q = quantiseColour(c[x]);
			(isLecturer ? lecturer_ : board_).add(q);
			if (judge) {
				++samples;
				misfits += (classifier.confidence(q) >= kConfidenceLecturer) != isLecturer;
			}
		}
	}
	lecturer_.endFrame();
	board_.endFrame();
	++frames_;

	double share = samples ? double(misfits) / samples : 0.0;
	bool due = false;
	if (derivations_ == 0) {
		due = frames_ >= settings_.initialFrames;
	} else if (baseline_ < 0.0) {
		// The first judged frame after a derivation sets the baseline.
		if (samples)
			baseline_ = misfit_ = share;
	} else {
		if (samples)
			misfit_ += kMisfitSmoothing * (share - misfit_);
		due = misfit_ > baseline_ + settings_.relearnMisfit;
	}
	if (!due || lecturer_.total() == 0 || board_.total() == 0)
		return false;
	deriveSignatures(lecturer_, board_, lab_, points_, classifier);
	++derivations_;
	baseline_ = -1.0;
	return true;
}

} // namespace depthkey
