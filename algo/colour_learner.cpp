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

// Colours more frequent (each class's counts over its own total) in the
// rival class are dropped from a class's samples before its signature is
// built, since SIOX's nearest-centroid rule lets even a small stray cluster
// claim a colour: they came from the seeds' errors
// (the board seen through the gap between arm and body, which the depth
// camera's coarse pixels call lecturer; an arm the depth camera did not
// seed, learned as board). Densities are compared in coarse cells (16
// levels per channel), since sensor noise scatters one surface over many
// fine cells.
constexpr int kCoarseShift = 2;
constexpr int kCoarseBits = kQuantBits - kCoarseShift;
constexpr double kRivalRatio = 1.0;

static uint32_t coarseCell(uint32_t quantised)
{
	constexpr uint32_t mask = (1u << kQuantBits) - 1;
	uint32_t r = (quantised >> (2 * kQuantBits)) & mask, g = (quantised >> kQuantBits) & mask, b = quantised & mask;
	return ((r >> kCoarseShift) << (2 * kCoarseBits)) | ((g >> kCoarseShift) << kCoarseBits) | (b >> kCoarseShift);
}

constexpr size_t kCoarseCells = size_t(1) << (3 * kCoarseBits);

SignatureScratch::SignatureScratch()
	: points(new WeightedLab[kQuantisedColours]), lecturerCells(kCoarseCells), boardCells(kCoarseCells)
{
}

static void coarseDensity(const DecayingHistogram &h, std::vector<uint64_t> &cells)
{
	std::fill(cells.begin(), cells.end(), uint64_t{ 0 });
	for (uint32_t i = 0; i < kQuantisedColours; ++i)
		if (uint32_t b = h.bin(i))
			cells[coarseCell(i)] += b;
}

static size_t collectUnrivalled(const DecayingHistogram &own, const std::vector<uint64_t> &ownCells,
				const std::vector<uint64_t> &rivalCells, double rivalScale,
				const QuantisedLab &lab, WeightedLab *out)
{
	size_t n = 0;
	for (uint32_t i = 0; i < kQuantisedColours; ++i) {
		uint32_t b = own.bin(i);
		if (!b)
			continue;
		uint32_t cell = coarseCell(i);
		if (double(rivalCells[cell]) * rivalScale > kRivalRatio * double(ownCells[cell]))
			continue;
		out[n++] = { lab[i], b };
	}
	return n;
}

void deriveSignatures(const DecayingHistogram &lecturer, const DecayingHistogram &board,
		      const QuantisedLab &lab, SignatureScratch &scratch, SioxClassifier &classifier)
{
	std::vector<uint64_t> &lecturerCells = scratch.lecturerCells, &boardCells = scratch.boardCells;
	WeightedLab *points = scratch.points.get();
	coarseDensity(lecturer, lecturerCells);
	coarseDensity(board, boardCells);
	// Densities: each class's counts over its own total.
	const double lt = double(std::max<uint64_t>(1, lecturer.total())), bt = double(std::max<uint64_t>(1, board.total()));
	size_t n = collectUnrivalled(lecturer, lecturerCells, boardCells, lt / bt, lab, points);
	classifier.lecturer().build(points, n);
	n = collectUnrivalled(board, boardCells, lecturerCells, bt / lt, lab, points);
	classifier.board().build(points, n);
	classifier.signaturesChanged();
}

ColourLearner::ColourLearner(const QuantisedLab &lab) : lab_(lab)
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

// True when no pixel marginPx away from (x, y), along the rows, columns and
// diagonals, carries a lecturer or undecided label (outside the image counts
// as board).
static bool farFromLecturer(const Gray8Image &trimap, int x, int y, int marginPx)
{
	const int w = trimap.width(), h = trimap.height();
	for (int dy = -marginPx; dy <= marginPx; dy += marginPx) {
		int yy = y + dy;
		if (yy < 0 || yy >= h)
			continue;
		const uint8_t *row = trimap.row(yy);
		for (int dx = -marginPx; dx <= marginPx; dx += marginPx) {
			int xx = x + dx;
			if (xx >= 0 && xx < w && row[xx] != kTrimapBoard)
				return false;
		}
	}
	return true;
}

bool ColourLearner::learn(const RgbImage &colour, const Gray8Image &trimap, int marginPx, SioxClassifier &classifier)
{
	const int w = colour.width(), h = colour.height();
	if (trimap.width() != w || trimap.height() != h)
		return false;
	marginPx = std::max(1, marginPx);
	int step = std::max(1, static_cast<int>(std::sqrt(double(w) * h / settings_.samples)));
	int offset = (frames_ * 7) % step; // jitter: a different sub-grid each frame
	bool judge = classifier.ready() && derivations_ > 0;
	unsigned samples = 0, misfits = 0;
	for (int y = offset; y < h; y += step) {
		const Rgb8 *c = colour.row(y);
		const uint8_t *t = trimap.row(y);
		for (int x = offset; x < w; x += step) {
			// The depth subset, graded or plain (algo/trimap.hpp).
			bool isLecturer = t[x] >= kTrimapSubset;
			if (!isLecturer && (t[x] != kTrimapBoard || !farFromLecturer(trimap, x, y, marginPx)))
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
	if (frames_ <= settings_.initialFrames) {
		// Still collecting: provisional signatures from what is in so far,
		// every frame, so SIOX works from the first frame on (better than
		// the raw depth superset), the last at initial_frames.
		due = true;
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
	deriveSignatures(lecturer_, board_, lab_, scratch_, classifier);
	++derivations_;
	baseline_ = -1.0;
	return true;
}

} // namespace depthkey
