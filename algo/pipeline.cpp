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
	if (!(settings.composite == settings_.composite) || settings.board.colour != settings_.board.colour)
		boardDirty_ = true;
	if (mapping.kind != mapping_.kind || mapping.x != mapping_.x || mapping.y != mapping_.y ||
	    mapping.colourWidth != mapping_.colourWidth || mapping.colourHeight != mapping_.colourHeight ||
	    mapping.tofWidth != mapping_.tofWidth || mapping.tofHeight != mapping_.tofHeight)
		mappingDirty_ = reseed = true;
	settings_ = settings;
	mapping_ = mapping;
	opacityQ8_ = opacityToQ8(settings.composite.opacity);
	seeder_.configure(settings.segmentation);
	seeded_ = false; // new settings: seed the next frame again
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
		seeded_ = false;
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
		uint32_t c = settings_.board.colour;
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
	// Seeds depend on the depth frame only; the colour camera runs faster,
	// so several colour frames share one depth frame, seeded once (and the
	// static background learns once per depth frame, as it should).
	const bool sameDepth = seeded_ && depth.timestampNs == seededNs_ && depth.sequence == seededSequence_ &&
			       (depth.timestampNs != 0 || depth.sequence != 0);
	if (!sameDepth) {
		seeder_.seed(depth, seeds_);
		seedMapper_.map(seeds_, trimap_, roi_);
		seeded_ = true;
		seededNs_ = depth.timestampNs;
		seededSequence_ = depth.sequence;
	}
	learner_.learn(colour.rgb, trimap_, settings_.learning.marginPx * seedMapper_.colourPixelsPerTofPixel(),
		       classifier_);
	// Until the first signatures exist (no lecturer or no board seen yet)
	// the classifier calls every colour lecturer: the output is the depth
	// superset, which never cuts the lecturer off.
	refiner_.setLecturerBeyondBorder(seedMapper_.lecturerBeyondBorder());
	refiner_.refine(colour.rgb, trimap_, roi_, classifier_, out.alpha);
	compose(colour.rgb, out);

	status_.learning = learner_.learning();
	status_.derivations = learner_.derivations();
	status_.bandPixels = refiner_.bandPixels();
	status_.lecturerCentroids = classifier_.lecturer().size();
	status_.boardCentroids = classifier_.board().size();
}

// Outside the ROI the alpha is 0: only the ROI is blended.
void Pipeline::compose(const RgbImage &colour, PipelineOutput &out) const
{
	compositeRoi(colour, out.alpha, board_, roi_, opacityQ8_, out.composite, kernelPath_);
	lecturerLayer(colour, out.alpha, out.lecturer, kernelPath_);
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
	out.composite.resize(colour.rgb.width(), colour.rgb.height());
	std::copy(colour.rgb.data(), colour.rgb.data() + colour.rgb.size(), out.composite.data());
	lecturerLayer(colour.rgb, out.alpha, out.lecturer, kernelPath_);
}

} // namespace depthkey
