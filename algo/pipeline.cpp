#include "algo/pipeline.hpp"

#include "algo/composite.hpp"
#include "algo/trimap_union.hpp"

#include <algorithm>

namespace depthkey {

Pipeline::Pipeline() : classifier_(lab_), learner_(lab_)
{
}

void Pipeline::configure(const PipelineSettings &settings, const MappingModel &mapping)
{
	bool reseed = !(settings.segmentation == settings_.segmentation) ||
		      !(settings.learning == settings_.learning);
	if (!(settings.composite == settings_.composite) || settings.boardColour != settings_.boardColour)
		boardDirty_ = true;
	if (!(mapping == mapping_))
		mappingDirty_ = reseed = true;
	settings_ = settings;
	mapping_ = mapping;
	opacityQ8_ = opacityToQ8(settings.composite.opacity);
	seeder_.configure(settings.segmentation);
	for (SeededDepth &s : seeded_)
		s.valid = false; // new settings: seed the next frames again
	learner_.configure(settings.learning);
	// With the guided filter on, the soft edge is the filter's: it rewrites
	// the whole ROI from the hard decision (alpha >= kConfidenceLecturer), and
	// the refiner's soft alpha keeps that side, so making it would be wasted.
	SioxSettings refinerSettings = settings.siox;
	if (settings.siox.guidedRadius > 0)
		refinerSettings.softAlpha = false;
	refiner_.configure(refinerSettings);
	refiner_.setGraphCut(settings.decision.cutSmoothness, settings.decision.cutEdgeSigma,
			     size_t(settings.decision.cutMaxBandPixels), settings.decision.cutLevels,
			     settings.decision.cutMargin);
	evidence_.configure(settings.decision);
	guided_.configure(settings.siox.guidedRadius, settings.siox.guidedEps);
	unmixing_.configure(settings.decision.edgeUnmixing);
	if (reseed)
		restartLearning();
}

void Pipeline::setBoardImage(const RgbImage &board)
{
	boardSource_ = board;
	boardDirty_ = true;
}

void Pipeline::setBoardGeometry(const Homography &colourToBoard, const RadialLens &lens, int boardWidth,
				int boardHeight)
{
	colourToBoard_ = colourToBoard;
	boardLens_ = lens;
	boardWidth_ = boardWidth;
	boardHeight_ = boardHeight;
	picturePrior_.clear(); // configured at the next frame's colour size
}

void Pipeline::clearBoardGeometry()
{
	boardWidth_ = boardHeight_ = 0;
	picturePrior_.clear();
}

void Pipeline::teachBoardFromPicture(const RgbImage &colour)
{
	status_.boardPictureTaught = false;
	if (!boardPicture_ || boardWidth_ <= 0)
		return;
	const int w = colour.width(), h = colour.height();
	if (!picturePrior_.configuredFor(w, h) &&
	    picturePrior_.configure(w, h, colourToBoard_, boardLens_, boardWidth_, boardHeight_) < 0)
		return;
	if (picturePrior_.predict(*boardPicture_, colour, boardModel_)) {
		boardModel_.teach(picturePrior_.sampled(), picturePrior_.gainQ8(), picturePrior_.onDisplay());
		status_.boardPictureTaught = true;
	}
}

void Pipeline::restartLearning()
{
	learner_.reset();
	classifier_.lecturer().clear();
	classifier_.board().clear();
	classifier_.signaturesChanged();
	boardModel_.reset();
	havePrevious_ = false;
}

void Pipeline::ensureSizes(int colourWidth, int colourHeight, int depthWidth, int depthHeight)
{
	if (colourWidth != colourWidth_ || colourHeight != colourHeight_ ||
	    depthWidth != depthWidth_ || depthHeight != depthHeight_ || mappingDirty_) {
		colourWidth_ = colourWidth;
		colourHeight_ = colourHeight;
		depthWidth_ = depthWidth;
		depthHeight_ = depthHeight;
		// A calibration made for other sizes cannot be used: identity
		// scaling for these sizes instead, and say so in the status.
		MappingModel model = mapping_;
		status_.mappingFits = model.colourWidth == colourWidth && model.colourHeight == colourHeight &&
				      model.tofWidth == depthWidth && model.tofHeight == depthHeight;
		if (!status_.mappingFits) {
			model = MappingModel{};
			model.colourWidth = colourWidth;
			model.colourHeight = colourHeight;
			model.tofWidth = depthWidth;
			model.tofHeight = depthHeight;
		}
		mapper_.configure(model);
		seedMapper_.configure(mapper_);
		mappingDirty_ = false;
		for (SeededDepth &s : seeded_)
			s.valid = false;
		boardDirty_ = true;
		restartLearning();
	}
	if (boardDirty_) {
		renderBoard(colourWidth, colourHeight);
		boardDirty_ = false;
	}
}

void Pipeline::renderBoard(int width, int height)
{
	if (boardSource_.empty()) {
		// A solid colour: one row of it serves every row (compositeRoi),
		// a colour frame's memory (0.9 MB at 640x480) not kept.
		board_ = RgbImage(width, 1);
		uint32_t c = settings_.boardColour;
		Rgb8 colour{ uint8_t(c >> 16), uint8_t(c >> 8), uint8_t(c) };
		std::fill(board_.data(), board_.data() + board_.size(), colour);
		return;
	}
	board_.resize(width, height);
	const int sw = boardSource_.width(), sh = boardSource_.height();
	for (int y = 0; y < height; ++y)
		for (int x = 0; x < width; ++x)
			board_.at(x, y) = boardSource_.at((2 * x + 1) * sw / (2 * width), (2 * y + 1) * sh / (2 * height));
}

const Pipeline::SeededDepth &Pipeline::seededFor(const DepthFrame &depth, const SeededDepth *keep)
{
	for (const SeededDepth &s : seeded_)
		if (s.holds(depth))
			return s;
	// Seeds depend on the depth frame only; the colour camera runs faster,
	// so several colour frames share one depth frame, seeded once (and the
	// static background learns once per depth frame, as it should).
	// The slot to reuse: not the other frame of this pair, else the older.
	const size_t slot = keep ? (keep == &seeded_[0] ? 1 : 0) : 1 - newest_;
	SeededDepth &s = seeded_[slot];
	seeder_.seed(depth, s.seeds);
	seedMapper_.map(s.seeds, s.mapped);
	s.ns = depth.timestampNs;
	s.sequence = depth.sequence;
	s.valid = true;
	newest_ = slot;
	return s;
}

void Pipeline::process(const ColourFrame &colour, const DepthFrame &depth, PipelineOutput &out)
{
	FramePairer::Bracket bracket;
	bracket.before = &depth;
	process(colour, bracket, out);
}

void Pipeline::process(const ColourFrame &colour, const FramePairer::Bracket &depth, PipelineOutput &out)
{
	const DepthFrame *first = depth.before ? depth.before : depth.after;
	const DepthFrame *second = depth.before && depth.after ? depth.after : nullptr;
	if (second && (second->depthMm.width() != first->depthMm.width() ||
		       second->depthMm.height() != first->depthMm.height()))
		second = nullptr; // the depth camera changed size in between
	ensureSizes(colour.rgb.width(), colour.rgb.height(), first->depthMm.width(), first->depthMm.height());
	const SeededDepth &a = seededFor(*first, nullptr);
	if (second) {
		// Where the colour frame lies between the two depth captures.
		const int64_t span = std::max<int64_t>(1, depth.afterNs - depth.beforeNs);
		const int64_t into = std::clamp<int64_t>(int64_t(colour.timestampNs) - depth.beforeNs, 0, span);
		uniteTrimaps(a.mapped, seededFor(*second, &a).mapped, int((into * 256 + span / 2) / span), keyed_);
	} else {
		uniteTrimaps(a.mapped, a.mapped, 0, keyed_);
	}
	const bool stale = depth.stale();
	if (stale)
		growSuperset(staleMarginPx(colour.rgb.width(), depth.staleNs));
	const Gray8Image &trimap = keyed_.trimap;
	const int marginPx = settings_.learning.marginPx * seedMapper_.colourPixelsPerTofPixel();
	// A stale trimap says where the lecturer was, not is: the colours under
	// it would teach the signatures and the board model wrong.
	if (!stale) {
		learner_.learn(colour.rgb, trimap, marginPx, classifier_);
		boardModel_.learn(colour.rgb, trimap);
	}
	teachBoardFromPicture(colour.rgb);
	// Until the first signatures exist (no lecturer or no board seen yet)
	// the classifier calls every colour lecturer: the output is the depth
	// superset, which never cuts the lecturer off.
	evidence_.bind(colour.rgb, keyed_.evidence, classifier_, boardModel_, havePrevious_ ? &previousAlpha_ : nullptr,
		       &previousColour_, previousRoi_);
	refiner_.setLecturerBeyondBorder(keyed_.lecturerBeyondBorder);
	refiner_.refine(colour.rgb, trimap, keyed_.roi, evidence_, out.alpha);
	if (settings_.siox.guidedRadius > 0)
		guideAlpha(colour.rgb, out.alpha);
	if (!stale)
		boardModel_.learnDecided(colour.rgb, trimap, out.alpha, keyed_.roi, marginPx);
	rememberFrame(colour.rgb, out.alpha);
	compose(colour.rgb, out);

	status_.learning = learner_.learning();
	status_.derivations = learner_.derivations();
	status_.bandPixels = refiner_.bandPixels();
	status_.lecturerCentroids = classifier_.lecturer().size();
	status_.boardCentroids = classifier_.board().size();
}

int Pipeline::staleMarginPx(int width, int64_t gapNs)
{
	const int64_t walked = int64_t{ width } * std::max<int64_t>(0, gapNs) / kCrossingNs;
	return static_cast<int>(std::min<int64_t>(walked, width / kMaxGrowthDivisor));
}

void Pipeline::growSuperset(int marginPx)
{
	Roi &roi = keyed_.roi;
	if (marginPx <= 0 || roi.empty())
		return; // depth saw no lecturer: nothing to follow
	Gray8Image &trimap = keyed_.trimap;
	dilateSquare(trimap, marginPx, grown_, morphology_, kernelPath_);
	roi = { std::max(0, roi.x0 - marginPx), std::max(0, roi.y0 - marginPx),
		std::min(trimap.width(), roi.x1 + marginPx), std::min(trimap.height(), roi.y1 + marginPx) };
	// Inside the grown superset nothing is sure: the lecturer may have
	// walked off the core and onto what depth saw as board. Depth's
	// evidence, where he was, says neither; colour decides.
	for (int y = roi.y0; y < roi.y1; ++y) {
		const uint8_t *g = grown_.row(y);
		uint8_t *t = trimap.row(y), *e = keyed_.evidence.row(y);
		for (int x = roi.x0; x < roi.x1; ++x) {
			if (!g[x])
				continue;
			t[x] = t[x] == kTrimapBoard ? kTrimapUndecided : std::min(t[x], kTrimapSubset);
			e[x] = kTrimapUndecided;
		}
	}
}

void Pipeline::guideAlpha(const RgbImage &colour, Gray8Image &alpha)
{
	// The decision, hard (the soft edge is the filter's to make).
	const Roi &roi = keyed_.roi;
	matte_.resize(alpha.width(), alpha.height());
	for (int y = roi.y0; y < roi.y1; ++y) {
		const uint8_t *a = alpha.row(y);
		uint8_t *m = matte_.row(y);
		for (int x = roi.x0; x < roi.x1; ++x)
			m[x] = a[x] >= kConfidenceLecturer ? 255 : 0;
	}
	unmixing_.refine(colour, keyed_.trimap, boardModel_, roi, matte_);
	guided_.filter(colour, matte_, roi, alpha);
}

void Pipeline::rememberFrame(const RgbImage &colour, const Gray8Image &alpha)
{
	previousAlpha_.resize(alpha.width(), alpha.height());
	previousColour_.resize(colour.width(), colour.height());
	const Roi &roi = keyed_.roi;
	for (int y = roi.y0; y < roi.y1; ++y) {
		std::copy(alpha.row(y) + roi.x0, alpha.row(y) + roi.x1, previousAlpha_.row(y) + roi.x0);
		std::copy(colour.row(y) + roi.x0, colour.row(y) + roi.x1, previousColour_.row(y) + roi.x0);
	}
	previousRoi_ = roi;
	havePrevious_ = true;
}

// Outside the ROI the alpha is 0: only the ROI is blended.
void Pipeline::compose(const RgbImage &colour, PipelineOutput &out) const
{
	if (makeComposite_)
		compositeRoi(colour, out.alpha, board_, keyed_.roi, opacityQ8_, out.composite, kernelPath_);
	else
		out.composite = RgbImage{}; // made where it goes (compositeInputs())
}

void Pipeline::confidence(const RgbImage &colour, Gray8Image &out) const
{
	out.resize(colour.width(), colour.height());
	for (size_t i = 0; i < colour.size(); ++i)
		out.data()[i] = classifier_.ready() ? classifier_.decideLab(lab_[quantiseColour(colour.data()[i])]) : 255;
}

void Pipeline::passThrough(const ColourFrame &colour, PipelineOutput &out)
{
	out.alpha.resize(colour.rgb.width(), colour.rgb.height());
	std::fill(out.alpha.data(), out.alpha.data() + out.alpha.size(), uint8_t(255));
	if (makeComposite_) {
		out.composite.resize(colour.rgb.width(), colour.rgb.height());
		std::copy(colour.rgb.data(), colour.rgb.data() + colour.rgb.size(), out.composite.data());
	} else {
		out.composite = RgbImage{}; // the colour frame itself
	}
}

} // namespace depthkey
