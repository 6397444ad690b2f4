#include "algo/pipeline.hpp"

#include "algo/composite.hpp"

#include <algorithm>

namespace depthkey {

Pipeline::Pipeline() : classifier_(lab_), learner_(lab_)
{
}

void Pipeline::configure(const Settings &settings, const MappingModel &mapping)
{
	bool reseed = !(settings.segmentation == settings_.segmentation) ||
		      !(settings.learning == settings_.learning);
	if (!(settings.composite == settings_.composite))
		boardDirty_ = true;
	if (mapping.kind != mapping_.kind || mapping.x != mapping_.x || mapping.y != mapping_.y ||
	    mapping.colourWidth != mapping_.colourWidth || mapping.colourHeight != mapping_.colourHeight ||
	    mapping.tofWidth != mapping_.tofWidth || mapping.tofHeight != mapping_.tofHeight)
		mappingDirty_ = reseed = true;
	settings_ = settings;
	mapping_ = mapping;
	opacityQ8_ = opacityToQ8(settings.composite.opacity);
	seeder_.configure(settings.segmentation, settings.learning);
	learner_.configure(settings.learning);
	refiner_.configure(settings.siox);
	if (reseed)
		restartLearning();
}

void Pipeline::setBoardImage(const RgbImage &board)
{
	boardSource_ = board;
	boardDirty_ = true;
}

void Pipeline::restartLearning()
{
	learner_.reset();
	classifier_.lecturer().clear();
	classifier_.board().clear();
	classifier_.signaturesChanged();
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
	board_.resize(width, height);
	if (boardSource_.empty()) {
		uint32_t c = settings_.composite.boardColour;
		Rgb8 colour{ uint8_t(c >> 16), uint8_t(c >> 8), uint8_t(c) };
		std::fill(board_.data(), board_.data() + board_.size(), colour);
		return;
	}
	const int sw = boardSource_.width(), sh = boardSource_.height();
	for (int y = 0; y < height; ++y)
		for (int x = 0; x < width; ++x)
			board_.at(x, y) = boardSource_.at((2 * x + 1) * sw / (2 * width), (2 * y + 1) * sh / (2 * height));
}

void Pipeline::process(const ColourFrame &colour, const DepthFrame &depth, PipelineOutput &out)
{
	ensureSizes(colour.rgb.width(), colour.rgb.height(), depth.depthMm.width(), depth.depthMm.height());
	seeder_.seed(depth, seeds_);
	seedMapper_.map(seeds_, depth.depthMm, trimap_, roi_);
	learner_.learn(colour.rgb, trimap_, seeds_.learnBoard, classifier_);
	// Until the first signatures exist the classifier calls every colour
	// lecturer: the output is the depth superset, which never cuts the
	// lecturer off.
	refiner_.refine(colour.rgb, trimap_, roi_, classifier_, out.alpha);
	compose(colour.rgb, out);

	status_.learning = learner_.derivations() == 0;
	status_.derivations = learner_.derivations();
	status_.bandPixels = refiner_.bandPixels();
	status_.lecturerCentroids = classifier_.lecturer().size();
	status_.boardCentroids = classifier_.board().size();
}

// Outside the ROI the alpha is 0, so the composite is the board there: only
// the ROI is blended (the lecturer is a fraction of the frame).
void Pipeline::compose(const RgbImage &colour, PipelineOutput &out) const
{
	const int w = colour.width(), h = colour.height();
	out.composite.resize(w, h);
	for (int y = 0; y < h; ++y) {
		Rgb8 *dst = out.composite.row(y);
		const Rgb8 *board = board_.row(y);
		if (roi_.empty() || y < roi_.y0 || y >= roi_.y1) {
			std::copy(board, board + w, dst);
			continue;
		}
		std::copy(board, board + roi_.x0, dst);
		compositeRow_C(colour.row(y) + roi_.x0, out.alpha.row(y) + roi_.x0, board + roi_.x0, opacityQ8_,
				  dst + roi_.x0, roi_.x1 - roi_.x0);
		std::copy(board + roi_.x1, board + w, dst + roi_.x1);
	}
	lecturerLayer(colour, out.alpha, out.lecturer);
}

void Pipeline::passThrough(const ColourFrame &colour, PipelineOutput &out)
{
	out.alpha.resize(colour.rgb.width(), colour.rgb.height());
	std::fill(out.alpha.data(), out.alpha.data() + out.alpha.size(), uint8_t(255));
	out.composite.resize(colour.rgb.width(), colour.rgb.height());
	std::copy(colour.rgb.data(), colour.rgb.data() + colour.rgb.size(), out.composite.data());
	lecturerLayer(colour.rgb, out.alpha, out.lecturer);
}

} // namespace depthkey
