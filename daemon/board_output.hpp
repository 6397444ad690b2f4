// The daemon's board: its source (hal/board/), its calibration (the
// homography file), and the board-geometry composite (algo/board_compositor).
// Wiring only: it decides which geometry the output is in and keeps the last
// good picture and the last good H when a new one is refused.
//
// Geometry: the board geometry needs an H fitted for this colour size and
// this board picture size; otherwise the composite stays in the colour
// camera's geometry (the pipeline's), the board picture is handed to the
// pipeline instead, and the status says "board not calibrated" and why.
#pragma once

#include "algo/board_compositor.hpp"
#include "algo/changed_rows.hpp"
#include "algo/pipeline.hpp"
#include "config/board_calibration_file.hpp"
#include "hal/camera.hpp"
#include "hal/frame_sink.hpp"
#include "hal/kernel_path_env.hpp"
#include "settings/settings.hpp"

#include <climits>
#include <functional>
#include <memory>
#include <optional>
#include <string>

namespace depthkey {

class BoardOutput
{
public:
	using SourceFactory = std::function<std::unique_ptr<ColourCamera>(const Settings &)>;
	using StatusHandler = std::function<void(const std::string &device, const DeviceStatus &)>;

	// onGeometry: the output streams' sizes changed (re-open them).
	void start(EventLoop &loop, const Settings &settings, SourceFactory factory, Pipeline &pipeline,
		   StatusHandler onStatus, std::function<void()> onGeometry);
	void stop();
	// On reload: the source restarts only when its settings changed; H is
	// read again (a refused file keeps the last good H).
	void apply(const Settings &settings);

	// Whether the pipeline is being keyed on the keying worker now
	// (daemon/keying_worker.hpp): a new picture then waits, by pointer to
	// the source's frame, until takeWaitingPicture() between frames. A
	// source that delivers from a frame of its own (the simulator, V4L2,
	// an image file) keeps it until its next frame or stop; one that
	// delivers a temporary (the solid colour) does so only in start(),
	// which runs between frames.
	void setPipelineBusy(std::function<bool()> busy) { pipelineBusy_ = std::move(busy); }
	void takeWaitingPicture();

	// The depth calibration file's [board] section (config/calibration_file.hpp),
	// or none: the H used while board.homography_file is empty. Takes
	// effect at the next start() or apply().
	void setCalibrationFileBoard(const std::optional<BoardCalibration> &board) { calibrationFileBoard_ = board; }

	// After the pipeline ran: makes its camera-geometry lecturer layer from
	// the colour frame and the alpha, and warps it into the board picture.
	// Does nothing in camera geometry (where the layer is made only in the
	// shared memory, hal/frame_sink.hpp).
	void compose(const RgbImage &colour, const Gray8Image &alpha, const Roi &roi, int opacityQ8);
	// The same frame made where it goes (FrameSink::publishBoard, issue
	// 29 §2): the camera-geometry layer is made now, the warp into the
	// slots the maker is lent; composite() and lecturer() keep an older
	// frame. Null in camera geometry. colour and alpha's layer is taken
	// now: the maker stays valid until the next call here.
	BoardFrameMaker *composeInPlace(const RgbImage &colour, const Gray8Image &alpha, const Roi &roi,
					int opacityQ8);
	// The board picture alone, the lecturer layer empty (NO SIGNAL frames).
	void showBoardOnly();

	bool boardGeometry() const { return compositor_.configured(); }
	int outputWidth() const { return compositor_.outputWidth(); }
	int outputHeight() const { return compositor_.outputHeight(); }
	const RgbImage &composite() const { return composite_; }
	const RgbaImage &lecturer() const { return lecturer_; }
	// The board's picture as the composite is made on it (the output size
	// in board geometry); empty for a solid colour in camera geometry.
	const RgbImage &picture() const { return outputPicture(); }
	// What the pipeline composites on in camera geometry (Pipeline::setBoardImage):
	// the picture, or none where the pipeline needs none.
	const RgbImage &pipelineBoard() const;

	bool sourceOk() const;
	std::string sourceName() const;   // "-" before start
	DeviceState sourceState() const;
	// "board sim-board streaming, board geometry 1920x780" or "...; board not calibrated (why)".
	std::string statusText() const;

private:
	void startSource();
	void onPicture(const ColourFrame &frame);
	void applyPicture(const ColourFrame &frame);
	void loadHomography();
	void updateGeometry();
	// changed: the picture's rows that differ from the last picture's.
	void scalePicture(RowRange changed = { 0, INT_MAX });
	const RgbImage &outputPicture() const { return scaled_.empty() ? picture_ : scaled_; }
	// [board] backend "colour": the picture is the [board] colour at
	// pictureWidth_ x pictureHeight_, its pixels (picture_) made only while
	// the board geometry composites on them.
	bool solidColour() const;
	void fillSolid(RgbImage &picture) const;

	EventLoop *loop_ = nullptr;
	Settings settings_;
	SourceFactory factory_;
	Pipeline *pipeline_ = nullptr;
	StatusHandler onStatus_;
	std::function<void()> onGeometry_;
	std::unique_ptr<ColourCamera> source_;
	std::function<bool()> pipelineBusy_;
	const ColourFrame *waitingPicture_ = nullptr; // the source's, taken between frames

	RgbImage picture_;            // last good board picture, the source's size
	ColourFrame spare_;           // lent to the source for its next picture (startSource())
	int pictureWidth_ = 0, pictureHeight_ = 0; // its size (also while a solid colour has no pixels)
	RgbImage scaled_;             // the picture at the output size; empty at the source's size
	BoardCalibration calibration_;
	bool haveCalibration_ = false; // last good H
	std::optional<BoardCalibration> calibrationFileBoard_;
	bool fromCalibrationFile_ = false; // calibration_ came from calibrationFileBoard_
	std::string notCalibrated_;    // why the composite is in camera geometry
	BoardCompositor compositor_;
	RgbaImage cameraLayer_;   // the lecturer layer in camera geometry, board geometry only
	KernelPath layerPath_ = kernelPathFromEnvironment();
	RgbImage composite_;
	RgbaImage lecturer_;
	ComposedBoardFrame inPlace_; // composeInPlace()'s: cameraLayer_ warped over the picture
};

} // namespace depthkey
