#include "daemon/board_output.hpp"

#include "algo/changed_rows.hpp"
#include "algo/composite.hpp"

#include "daemon/log.hpp"
#include "hal/sim/board_display.hpp"

#include <algorithm>
#include <cstring>
#include <utility>

namespace depthkey {

namespace {

// The picture size before the first picture arrives: what the source will
// deliver, so that the geometry (and the output streams) are right at once.
void expectedSize(const BoardSettings &b, int &width, int &height)
{
	width = b.width;
	height = b.backend == "sim" ? simBoardHeight(b.width) : b.height;
}

bool sameSource(const Settings &a, const Settings &b)
{
	BoardSettings x = a.board, y = b.board;
	x.outputWidth = y.outputWidth = x.outputHeight = y.outputHeight = 0;
	x.homographyFile = y.homographyFile = "";
	return x == y && (a.board.backend != "sim" || a.sim == b.sim);
}

std::string sizeText(int w, int h)
{
	return std::to_string(w) + "x" + std::to_string(h);
}

} // namespace

void BoardOutput::start(EventLoop &loop, const Settings &settings, SourceFactory factory, Pipeline &pipeline,
			StatusHandler onStatus, std::function<void()> onGeometry)
{
	loop_ = &loop;
	settings_ = settings;
	factory_ = std::move(factory);
	pipeline_ = &pipeline;
	onStatus_ = std::move(onStatus);
	onGeometry_ = std::move(onGeometry);
	expectedSize(settings.board, pictureWidth_, pictureHeight_);
	picture_ = RgbImage();
	if (!solidColour())
		fillSolid(picture_);
	loadHomography();
	updateGeometry();
	startSource();
}

void BoardOutput::stop()
{
	waitingPicture_ = nullptr; // the source's frame goes with it
	if (source_)
		source_->stop();
}

void BoardOutput::startSource()
{
	stop();
	source_ = factory_(settings_);
	// A source that makes its pictures in storage lent to it (the
	// simulated board; hal/camera.hpp) makes them in spare_, which
	// applyPicture() swaps with picture_ rather than copy (4.5 MB a
	// picture at 1920x780). The others' pictures are copied.
	// Not while spare_ holds a picture that waits for keying to finish: the
	// simulated board renders on a thread of its own (hal/sim/
	// sim_render_thread.hpp) and would write over it while the loop takes
	// it; the source then makes that picture in its own storage.
	source_->lendFrames(
		[this]() -> ColourFrame * { return solidColour() || waitingPicture_ == &spare_ ? nullptr : &spare_; });
	std::string name = source_->name();
	int ret = source_->start(
		*loop_, [this](const ColourFrame &f) { onPicture(f); },
		[this, name](const DeviceStatus &s) { onStatus_(name, s); });
	if (ret < 0)
		onStatus_(name, { DeviceState::Lost, ret, "cannot start" });
	else
		logger().info("board source " + name + " started", { { "DEVICE", name } });
}

void BoardOutput::apply(const Settings &next)
{
	bool restart = !sameSource(settings_, next);
	settings_ = next;
	loadHomography();
	updateGeometry();
	if (restart)
		startSource();
}

void BoardOutput::onPicture(const ColourFrame &frame)
{
	// The pipeline samples picture_ while it keys: a new one waits.
	if (pipelineBusy_ && pipelineBusy_()) {
		waitingPicture_ = &frame;
		return;
	}
	waitingPicture_ = nullptr;
	applyPicture(frame);
}

void BoardOutput::takeWaitingPicture()
{
	if (const ColourFrame *frame = std::exchange(waitingPicture_, nullptr))
		applyPicture(*frame);
}

void BoardOutput::applyPicture(const ColourFrame &frame)
{
	bool resized = frame.rgb.width() != pictureWidth_ || frame.rgb.height() != pictureHeight_;
	pictureWidth_ = frame.rgb.width();
	pictureHeight_ = frame.rgb.height();
	// What changed since the last picture, where only that is copied and
	// sampled again: in board geometry at the same size (a new size or
	// geometry takes the whole picture anyway).
	const bool rowsMatter = !resized && boardGeometry();
	RowRange changed{ 0, pictureHeight_ - 1 };
	if (!solidColour() && &frame == &spare_) {
		std::swap(picture_, spare_.rgb); // the next picture is made over the last one
		if (rowsMatter)
			changed = changedRows(spare_.rgb, picture_);
	} else if (!solidColour()) {
		if (rowsMatter)
			changed = changedRows(picture_, frame.rgb);
		picture_ = frame.rgb; // same size: no allocation
	} else if (!picture_.empty())
		fillSolid(picture_);
	if (resized)
		updateGeometry();
	if (boardGeometry()) {
		scalePicture(changed);
		if (pipeline_ && !resized) { // a new picture in place
			if (pipeline_->boardPicture() == &picture_)
				pipeline_->boardPictureRowsChanged(changed.first, changed.last);
			else
				pipeline_->setBoardPicture(&picture_);
		}
	} else if (pipeline_)
		pipeline_->setBoardImage(pipelineBoard());
}

void BoardOutput::loadHomography()
{
	const std::string &path = settings_.board.homographyFile;
	if (path.empty()) {
		// The depth calibration file may carry the board's H (the same
		// session fitted both: depthkey-calibrate --sim).
		const bool wasFromCalibrationFile = haveCalibration_ && fromCalibrationFile_;
		haveCalibration_ = fromCalibrationFile_ = calibrationFileBoard_.has_value();
		if (haveCalibration_) {
			calibration_ = *calibrationFileBoard_;
			const std::string text = "board calibration from mapping.calibration_file's [board]: " +
						 sizeText(calibration_.boardWidth, calibration_.boardHeight) +
						 " board px, fitted rms " + std::to_string(calibration_.rmsPx) + " px";
			const std::string &file = settings_.mapping.calibrationFile;
			if (logger().errorActive("board_calibration"))
				logger().clearError("board_calibration", text,
						    { { "DEVICE", "board_calibration" }, { "CALIBRATION_FILE", file } });
			else if (!wasFromCalibrationFile) // said once, not at every reload
				logger().info(text, { { "DEVICE", "board_calibration" }, { "CALIBRATION_FILE", file } });
		} else {
			logger().clearError("board_calibration", "board calibration no longer used",
					    { { "DEVICE", "board_calibration" } });
		}
		return;
	}
	BoardCalibrationResult result = loadBoardCalibration(path);
	if (!result.ok()) {
		logger().errorOnce("board_calibration",
				   "board calibration refused: " + result.errors.front().toString() +
					   (haveCalibration_ ? "; keeping the previous one" : "; compositing in camera geometry"),
				   { { "DEVICE", "board_calibration" }, { "CALIBRATION_FILE", path } });
		return;
	}
	calibration_ = result.calibration;
	haveCalibration_ = true;
	fromCalibrationFile_ = false;
	logger().clearError("board_calibration",
			    "board calibration loaded: " + sizeText(calibration_.boardWidth, calibration_.boardHeight) +
				    " board px, fitted rms " + std::to_string(calibration_.rmsPx) + " px",
			    { { "DEVICE", "board_calibration" }, { "CALIBRATION_FILE", path } });
}

void BoardOutput::updateGeometry()
{
	const int cw = settings_.colour.width, ch = settings_.colour.height;
	const int pw = pictureWidth_, ph = pictureHeight_;
	const int ow = settings_.board.outputWidth ? settings_.board.outputWidth : pw;
	const int oh = settings_.board.outputHeight ? settings_.board.outputHeight : ph;
	const BoardCalibration &c = calibration_;
	if (!haveCalibration_)
		notCalibrated_ = settings_.board.homographyFile.empty()
					 ? "board.homography_file is empty and the calibration file has no [board]"
					 : "no usable board calibration";
	else if (c.colourWidth != cw || c.colourHeight != ch)
		notCalibrated_ = "calibrated for colour " + sizeText(c.colourWidth, c.colourHeight) + ", the camera gives " +
				 sizeText(cw, ch);
	else if (c.boardWidth != pw || c.boardHeight != ph)
		notCalibrated_ = "calibrated for a board picture of " + sizeText(c.boardWidth, c.boardHeight) +
				 ", the source gives " + sizeText(pw, ph);
	else
		notCalibrated_.clear();

	int before = outputWidth() * 100000 + outputHeight();
	if (notCalibrated_.empty() &&
	    compositor_.configure(c.colourToBoard.then(boardScaling(pw, ph, ow, oh)), cw, ch, ow, oh, c.lens())) {
		// At the source's size the picture itself is the output's: no
		// second copy of it (4.5 MB for the simulated board's 1920x780).
		if (ow == pw && oh == ph)
			scaled_ = RgbImage();
		else
			scaled_.resize(ow, oh);
		scalePicture();
		showBoardOnly();
		if (pipeline_) {
			pipeline_->setBoardImage(RgbImage()); // the camera-geometry composite is not published
			// The board model is taught what the picture predicts
			// (algo/board_picture_prior.hpp); picture_ is kept in place.
			pipeline_->setBoardGeometry(c.colourToBoard, c.lens(), pw, ph);
			pipeline_->setBoardPicture(picture_.width() == pw && picture_.height() == ph ? &picture_ : nullptr);
		}
	} else {
		if (notCalibrated_.empty())
			notCalibrated_ = "the board calibration's homography is singular";
		compositor_.clear();
		if (solidColour())
			picture_ = RgbImage(); // the pipeline fills its board with the colour itself
		if (pipeline_) {
			pipeline_->setBoardImage(pipelineBoard());
			pipeline_->clearBoardGeometry();
			pipeline_->setBoardPicture(nullptr);
		}
	}
	if (outputWidth() * 100000 + outputHeight() != before && onGeometry_)
		onGeometry_();
}

// Nearest neighbour, pixel centres kept; nothing to do at the same size
// (outputPicture() is the picture then, and the next composites copy only
// its changed rows; a scaled picture is copied whole).
void BoardOutput::scalePicture(RowRange changed)
{
	if (!scaled_.empty())
		changed = { 0, scaled_.height() - 1 };
	compositor_.forgetBoardRows(changed.first, changed.last);
	if (scaled_.empty())
		return;
	const int sw = picture_.width(), sh = picture_.height(), dw = scaled_.width(), dh = scaled_.height();
	for (int y = 0; y < dh; ++y) {
		const Rgb8 *src = picture_.row(int((2 * int64_t(y) + 1) * sh / (2 * dh)));
		Rgb8 *dst = scaled_.row(y);
		for (int x = 0; x < dw; ++x)
			dst[x] = src[(2 * int64_t(x) + 1) * sw / (2 * dw)];
	}
}

void BoardOutput::compose(const RgbImage &colour, const Gray8Image &alpha, const Roi &roi, int opacityQ8)
{
	if (!boardGeometry())
		return;
	lecturerLayer(colour, alpha, cameraLayer_, layerPath_);
	compositor_.compose(cameraLayer_, roi, outputPicture(), opacityQ8, composite_, lecturer_);
}

BoardFrameMaker *BoardOutput::composeInPlace(const RgbImage &colour, const Gray8Image &alpha, const Roi &roi,
					     int opacityQ8)
{
	if (!boardGeometry())
		return nullptr;
	lecturerLayer(colour, alpha, cameraLayer_, layerPath_);
	inPlace_.compositor = &compositor_;
	inPlace_.layer = &cameraLayer_;
	inPlace_.roi = roi;
	inPlace_.board = &outputPicture();
	inPlace_.opacityQ8 = opacityQ8;
	return &inPlace_;
}

void BoardOutput::showBoardOnly()
{
	if (!boardGeometry())
		return;
	composite_ = outputPicture();
	lecturer_.resize(composite_.width(), composite_.height());
	std::fill(lecturer_.data(), lecturer_.data() + lecturer_.size(), Rgba8{ 0, 0, 0, 0 });
	compositor_.forgetLayer();
	compositor_.forgetBoard();
}

// A solid colour needs no picture in the pipeline: with none it fills the
// board with the same [board] colour at the frame's size, and keeps no copy
// of a board-sized picture (6.2 MB at the default 1920x1080). In board
// geometry the pipeline's composite is not published: no picture either.
const RgbImage &BoardOutput::pipelineBoard() const
{
	static const RgbImage none;
	return boardGeometry() || solidColour() ? none : picture_;
}

bool BoardOutput::solidColour() const
{
	return settings_.board.backend == "colour";
}

void BoardOutput::fillSolid(RgbImage &picture) const
{
	picture.resize(pictureWidth_, pictureHeight_);
	uint32_t c = settings_.board.colour;
	std::fill(picture.data(), picture.data() + picture.size(), Rgb8{ uint8_t(c >> 16), uint8_t(c >> 8), uint8_t(c) });
}

bool BoardOutput::sourceOk() const
{
	return source_ && source_->status().state == DeviceState::Streaming;
}

std::string BoardOutput::sourceName() const
{
	return source_ ? source_->name() : std::string("-");
}

DeviceState BoardOutput::sourceState() const
{
	return source_ ? source_->status().state : DeviceState::Stopped;
}

std::string BoardOutput::statusText() const
{
	std::string text = "board " + sourceName() + " " + deviceStateName(sourceState());
	if (sourceState() == DeviceState::Lost)
		text += " (last good picture kept)";
	if (boardGeometry())
		return text + ", board geometry " + sizeText(outputWidth(), outputHeight());
	return text + "; board not calibrated (" + notCalibrated_ + ")";
}

} // namespace depthkey
