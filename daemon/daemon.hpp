// depthkeyd's wiring: one event loop, the devices behind hal/ interfaces, the
// pipeline (keyed on a worker thread of its own: daemon/keying_worker.hpp,
// daemon_keying.cpp), shared-memory output, status for systemd and the LEDs.
// It holds no algorithm; it decides what to run when, and degrades instead
// of dying.
#pragma once

#include "algo/live_score.hpp"
#include "algo/pipeline.hpp"
#include "daemon/board_output.hpp"
#include "daemon/command_line_overrides.hpp"
#include "daemon/config_reloader.hpp"
#include "daemon/device_factory.hpp"
#include "daemon/frame_outputs.hpp"
#include "daemon/frame_pairing.hpp"
#include "daemon/frame_recorder.hpp"
#include "daemon/keying_worker.hpp"
#include "daemon/no_signal_picture.hpp"
#include "daemon/preview_feed.hpp"
#include "daemon/setup_tracker.hpp"
#include "daemon/stage_dumps.hpp"
#include "daemon/status_lights.hpp"
#include "daemon/status_reporter.hpp"
#include "daemon/test_fault.hpp"
#include "hal/camera.hpp"
#include "hal/event_loop.hpp"
#include "hal/v4l2/v4l2_output.hpp"
#include "settings/settings.hpp"
#include "wiring/pipeline_setup.hpp"

#include <atomic>
#include <memory>
#include <optional>
#include <string>
#include <utility>

namespace depthkey {

class Daemon
{
public:
	Daemon(std::string configPath, CommandLineOverrides overrides, DeviceFactory factory = {})
		: configPath_(std::move(configPath)), overrides_(std::move(overrides)),
		  factory_(std::move(factory)),
		  reloader_(loop_, status_, configPath_, overrides_,
			    [this](const Settings &s, const PipelineFiles &f) { apply(s, f); }),
		  outputs_(factory_.frameSink), lights_(factory_.statusLeds), setup_(configPath_) {}
	~Daemon();

	// Sets up the loop, signals, devices and output. A negative errno means
	// the daemon cannot run at all (no event loop, or -EBUSY: another writer
	// holds its shared memory); missing cameras do not fail here, they are
	// reported and retried.
	int start(const Settings &settings);
	// Why start() failed, naming what, when it knows more than the errno.
	const std::string &startError() const { return startError_; }
	int run(); // until SIGTERM/SIGINT; returns the exit status

	// For tests that drive the daemon from its own loop.
	EventLoop &loop() { return loop_; }

private:
	void onColourFrame(const ColourFrame &frame);
	void onDepthFrame(const DepthFrame &frame);
	// Hands every held colour frame that is due to the keying worker, then
	// arms a timer for the next one (pairing.delay_ms).
	void keyDueFrames(bool makeRoom = false);
	// On the keying worker (daemon_keying.cpp): the pipeline alone.
	void keyOnWorker(KeyingJob &job);
	// On the loop: a keyed frame's board warp, previews and publication.
	void onKeyed(KeyingJob &job);
	// On the loop, while the pipeline is its own (the worker idle or
	// waiting for onKeyed to return): what waited for it.
	void betweenFrames();
	void applyNow(const Settings &settings, const PipelineFiles &files);
	void onDeviceStatus(const std::string &device, const DeviceStatus &status);
	void onFrameTick();
	void onStatusTick();
	void onReaderTick();
	PipelineView pipelineView() const
	{
		return { pipeline_, output_, mapping_, publishedComposite(nullptr, true), &board_.picture() };
	}
	void askForSnapshot(); // SIGUSR1 or the preview's button: written between frames
	void updateRecording();
	void checkRecording();
	void injectTestFault();
	void stop();

	int openOutput();
	OutputGeometry outputGeometry() const;
	void startWebcam(); // output.v4l2_device
	void startCameras();
	void stopCameras();
	void apply(const Settings &settings, const PipelineFiles &files);
	void applyPipelineFiles(const PipelineFiles &files);
	void checkCalibrationFits();
	// colour: the frame, the lecturer layer's colours; null for NO SIGNAL.
	// parts: the keyed frame's composite parts; null when it went out
	// without depth (the colour frame is the composite) and for NO SIGNAL.
	void scorePublished(const ColourFrame &frame, bool keyed);
	// boardMaker: board geometry made where it goes (BoardOutput::composeInPlace).
	void publish(const RgbImage *colour, const CompositeInputs *parts, uint64_t captureNs, uint32_t flags,
		     BoardFrameMaker *boardMaker = nullptr);
	// The composite publish() sends: the board's in board geometry, else the
	// pipeline's image when it made one (NO SIGNAL's too), else none when it
	// is made from its parts in the shared memory, or (no depth) the colour frame.
	const RgbImage *publishedComposite(const RgbImage *colour, bool fromParts) const;
	// The same pictures for the preview page (issue 30).
	RecordedPictures recordedPictures(const RgbImage *colour, bool fromParts) const;
	// Whether the pipeline's composite image is read by more than the
	// recorder's shared memory this frame (preview, virtual webcam, stage dumps).
	bool compositeReadHere(uint64_t nowNs) const;
	// Whether the board geometry's composite and layer are read here too
	// (virtual webcam, preview, stage dumps, a snapshot): made as images
	// then, else only in the shared memory (issue 29 §2).
	bool boardImagesReadHere(uint64_t nowNs) const;
	void publishNoSignal(uint64_t nowNs);
	StatusSummary summary() const;
	StatusSnapshot statusSnapshot() const;
	// Whether the depth and the board are calibrated, as the daemon runs.
	CalibrationFacts calibrationFacts() const;

	std::string configPath_;
	CommandLineOverrides overrides_;
	DeviceFactory factory_;
	Settings settings_;
	EventLoop loop_;
	StatusReporter status_; // STATUS=, READY, the watchdog, the counters
	ConfigReloader reloader_; // SIGHUP

	std::unique_ptr<ColourCamera> colour_;
	std::unique_ptr<DepthCamera> depth_;
	FrameOutputs outputs_;  // the shared-memory streams; readers sampled every 250 ms
	V4l2Output webcam_;     // the composite to a v4l2loopback node, when configured
	StatusLights lights_;
	SetupTracker setup_; // the first-run path's state, for status.json (issue 30)

	EventSource sigterm_, sigint_, sighup_, sigusr1_, sigusr2_;
	EventSource keyTimer_;
	EventSource frameTick_, statusTick_, readerTick_;

	// The live preview page and what only it reports.
	PreviewFeed preview_;

	FrameRecorder recorder_;
	uint64_t recorderDropsLogged_ = 0;
	std::string startError_;
	StageDumps stageDumps_; // SIGUSR1 snapshots, --preview stage images

	Pipeline pipeline_;
	BoardOutput board_;        // the board's picture, H and board-geometry composite
	MappingModel mapping_;     // the last good calibration, or identity
	bool calibrated_ = false;
	int colourWidth_ = 0, colourHeight_ = 0, depthWidth_ = 0, depthHeight_ = 0; // last frames
	PipelineOutput output_;
	// Each published frame against its truth, when the colour source knows
	// it (issue 29); the board-only frames published after depth first came.
	LiveScore liveScore_;
	uint64_t boardOnlyFrames_ = 0;
	bool depthKeyed_ = false;
	FramePairing pairing_;     // colour frames waiting for depth, the depth camera's offset
	PipelineStatus pipelineStatus_; // the pipeline's, as of the last keyed frame (loop's copy)
	// A reload that came while a frame was being keyed, applied between frames.
	std::optional<std::pair<Settings, PipelineFiles>> pendingReload_;
	bool snapshotWanted_ = false; // SIGUSR1 while a frame was being keyed
	bool submitting_ = false;     // in keyDueFrames: the pairing queue is being read
	bool inResult_ = false;       // in onKeyed: the pipeline is the loop's
	bool haveColour_ = false;
	uint64_t lastColourNs_ = 0;   // arrival (loop clock) of the last colour frame
	uint64_t lastFrameTickNs_ = 0; // loop clock of the last onFrameTick
	uint64_t loopResumedNs_ = 0;   // when the loop last resumed after being held
	NoSignalPicture noSignal_;

	TestFault testFault_ = TestFault::None;
	std::atomic<bool> keyingStalled_{ false }; // TEST-ONLY "stall" fault injected; read on the worker

	// Last: joined (in ~Daemon, before anything it keys with goes) while
	// the pipeline, its output and the loop are still there.
	KeyingWorker keyer_;
};

} // namespace depthkey
