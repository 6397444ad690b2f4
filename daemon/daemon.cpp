#include "daemon/daemon.hpp"

#include "algo/composite.hpp"
#include "daemon/log.hpp"
#include "hal/depthkey_shm.h"
#include "wiring/pipeline_setup.hpp"

#include <algorithm>
#include <csignal>

namespace depthkey {

namespace {

// Without a colour frame for this many frame periods, and at least
// kColourStaleMinNs, publish NO SIGNAL. One lost or error-flagged buffer is
// two periods without a frame (80 ms at 25 fps), and a loaded box adds the
// time a keying holds the loop: the HIL suite saw a NO SIGNAL frame for one
// error buffer (webcam-error-buffer-dropped) with three periods alone; and
// a held loop restarts the grace (onFrameTick).
constexpr uint64_t kColourStalePeriods = 3;
constexpr uint64_t kColourStaleMinNs = 250'000'000;
// Reader heartbeats are sampled this often: a dead reader is gone within
// DK_SHM_READER_TIMEOUT_MS plus this.
constexpr uint64_t kReaderTickUs = 250'000;

} // namespace

Daemon::~Daemon()
{
	keyer_.stop();
	preview_.stop();
	recorder_.stop();
	stopCameras();
	board_.stop();
	outputs_.close();
	lights_.close();
}

int Daemon::start(const Settings &settings)
{
	settings_ = settings;
	overrides_.applyTo(settings_);
	LogLevel level;
	if (parseLogLevel(settings.daemon.logLevel, level))
		logger().setLevel(level);

	int ret = loop_.open();
	if (ret < 0)
		return ret;
	ret = EventLoop::blockSignals({ SIGTERM, SIGINT, SIGHUP, SIGUSR1 });
	if (ret < 0)
		return ret;
	// SIGUSR2 keeps its default action (terminate) unless a test armed a fault.
	testFault_ = testFaultFromEnvironment();
	if (testFault_ != TestFault::None && EventLoop::blockSignals({ SIGUSR2 }) == 0)
		loop_.addSignal(SIGUSR2, [this] { injectTestFault(); }, sigusr2_);
	loop_.addSignal(SIGTERM, [this] { stop(); }, sigterm_);
	loop_.addSignal(SIGINT, [this] { stop(); }, sigint_);
	loop_.addSignal(SIGHUP, [this] { reloader_.reload(); }, sighup_);
	loop_.addSignal(SIGUSR1, [this] { askForSnapshot(); }, sigusr1_);

	status_.start(loop_);
	// One worker, one frame waiting for it: a frame more would add a
	// keying's latency and a frame's memory (0.9 MB at 640x480) for
	// little: the pairing ring already absorbs the cameras' jitter.
	ret = keyer_.start(
		loop_, 1, [this](KeyingJob &job) { keyOnWorker(job); }, [this](KeyingJob &job) { onKeyed(job); });
	if (ret < 0)
		return ret;
	board_.setPipelineBusy([this] { return !inResult_ && !keyer_.idle(); });
	stageDumps_.setFolders(settings_.daemon.snapshotDir, overrides_.previewDir);
	applyPipelineFiles(loadPipelineFiles(settings_));
	pairing_.configure(settings_);
	lights_.open(loop_, settings_);

	board_.start(
		loop_, settings_, factory_.boardSource, pipeline_,
		[this](const std::string &name, const DeviceStatus &s) { onDeviceStatus(name, s); },
		[this] { // the composite's geometry or size changed
			outputs_.reopen(settings_, outputGeometry());
		});
	// A second instance on our preview port (with output names of its own):
	// exit before creating anything, not serve no page (issue 30).
	if (int ret = preview_.apply(settings_.preview, &startError_); ret == -EADDRINUSE)
		return ret;
	// Another writer on our names (a second depthkeyd): exit, not run at 0 fps.
	if (int ret = openOutput(); ret == -EBUSY) {
		startError_ = outputs_.describeError();
		return ret;
	}
	startWebcam();
	updateRecording();
	startCameras();

	loop_.addPeriodic(1000000u / settings_.colour.fps, [this] { onFrameTick(); }, frameTick_);
	loop_.addPeriodic(1000000u, [this] { onStatusTick(); }, statusTick_);
	loop_.addPeriodic(kReaderTickUs, [this] { onReaderTick(); }, readerTick_);

	logger().info("depthkeyd started", { { "CONFIG_FILE", configPath_ } });
	return 0;
}

int Daemon::run()
{
	int ret = loop_.run();
	status_.stopping();
	keyer_.stop(); // a frame being keyed is finished first
	preview_.stop();
	stopCameras();
	board_.stop();
	recorder_.stop();
	outputs_.remove(); // a clean stop leaves nothing in /dev/shm (docs/shared-memory.md)
	logger().info("depthkeyd stopped");
	return ret < 0 ? 1 : ret;
}

void Daemon::stop()
{
	status_.stopping();
	loop_.exit(0);
}

int Daemon::openOutput()
{
	return outputs_.open(settings_, outputGeometry());
}

OutputGeometry Daemon::outputGeometry() const
{
	return { settings_.colour.width, settings_.colour.height, board_.outputWidth(), board_.outputHeight() };
}

void Daemon::startWebcam()
{
	webcam_.start(loop_, settings_.output.v4l2Device, [this](const DeviceStatus &s) {
		if (s.state == DeviceState::Stopped)
			logger().clearError("v4l2-output", "v4l2-output off", { { "DEVICE", "v4l2-output" } });
		else
			onDeviceStatus("v4l2-output", s);
	});
}

void Daemon::startCameras()
{
	colour_ = factory_.colourCamera(settings_);
	depth_ = factory_.depthCamera(settings_);
	std::string colourName = colour_->name(), depthName = depth_->name();
	// The colour camera makes its frame in the pairing ring's free slot: no
	// copy, and no frame buffer of its own beside the ring (0.9 MB at
	// 640x480). A full ring keys its oldest frame first, as onColourFrame
	// does for a frame made elsewhere, only before the new frame is made
	// rather than after: the simulator's frames arrive a render (10-20 ms)
	// after their capture, so at 25 fps and 150 ms the oldest is still
	// waiting when the next capture starts, though 160 ms after its own.
	// The simulator renders it on its own thread (hal/sim/sim_render_thread.hpp)
	// while the loop goes on pairing and keying: the queue leaves that slot
	// alone until the frame is delivered here, and stopCameras() stops the
	// camera (waiting for its render) before it clears the ring.
	colour_->lendFrames([this]() -> ColourFrame * {
		keyDueFrames(true);
		return pairing_.queue().freeSlot();
	});
	int ret = colour_->start(
		loop_, [this](const ColourFrame &f) { onColourFrame(f); },
		[this, colourName](const DeviceStatus &s) { onDeviceStatus(colourName, s); });
	if (ret < 0)
		onDeviceStatus(colourName, { DeviceState::Lost, ret, "cannot start" });
	else
		logger().info("colour camera " + colourName + " started", { { "DEVICE", colourName } });
	ret = depth_->start(
		loop_, [this](const DepthFrame &f) { onDepthFrame(f); },
		[this, depthName](const DeviceStatus &s) { onDeviceStatus(depthName, s); });
	if (ret < 0)
		onDeviceStatus(depthName, { DeviceState::Lost, ret, "cannot start" });
	else
		logger().info("depth camera " + depthName + " started", { { "DEVICE", depthName } });
}

void Daemon::stopCameras()
{
	if (colour_)
		colour_->stop();
	if (depth_)
		depth_->stop();
	haveColour_ = false;
	pairing_.clear();
	keyTimer_.reset();
}

void Daemon::onDeviceStatus(const std::string &device, const DeviceStatus &status)
{
	status_.countDeviceStatus(device, status);
	// Depth lost: the offset estimator's history would span the gap (or
	// hold what came before junk), so it starts again when depth is back.
	if (status.state == DeviceState::Lost && depth_ && device == depth_->name())
		pairing_.forgetLatency();
	setup_.invalidate();
	if (status.state == DeviceState::Lost) {
		// Not there at all (never plugged in, unplugged): the journal
		// says which device and the next step (docs/first-run.md).
		const char *role = colour_ && device == colour_->name() ? "colour camera" : "depth camera";
		std::optional<PreviewSetupDevice> missing = setup_.missing(settings_, calibrationFacts(), role);
		logger().errorOnce(device, missing ? missingDeviceLine(*missing) : device + " lost: " + status.detail,
				   { { "DEVICE", device }, { "ERROR", errnoText(status.error) } });
	} else if (status.state == DeviceState::Streaming) {
		logger().clearError(device, device + " streaming again", { { "DEVICE", device } });
	}
	lights_.show(summary());
}

void Daemon::onDepthFrame(const DepthFrame &frame)
{
	depthWidth_ = frame.depthMm.width();
	depthHeight_ = frame.depthMm.height();
	pairing_.addDepth(frame);
	recorder_.recordDepth(frame);
	status_.countDepthFrame(frame.timestampNs, loop_.nowUs() * 1000u);
	keyDueFrames();
}

void Daemon::onColourFrame(const ColourFrame &frame)
{
	status_.countColourFrame();
	haveColour_ = true;
	colourWidth_ = frame.rgb.width();
	colourHeight_ = frame.rgb.height();
	recorder_.recordColour(frame);
	lastColourNs_ = loop_.nowUs() * 1000u; // when it came: a late camera clock must not look stale
	// A full ring keys its oldest frame first, early, rather than lose it.
	keyDueFrames(true);
	pairing_.addColour(frame, loop_.nowUs() * 1000u);
	keyDueFrames();
}

// Runs at the colour frame rate: when colour frames stop (camera lost or
// stalled), keep the recorder fed with a NO SIGNAL frame marked offline.
// SIGUSR1, or the preview page's snapshot button.
void Daemon::askForSnapshot()
{
	snapshotWanted_ = true; // the stage images are the worker's while it keys
	if (keyer_.idle())
		betweenFrames();
}

void Daemon::onFrameTick()
{
	uint64_t nowNs = loop_.nowUs() * 1000u;
	if (preview_.snapshotPending() && !snapshotWanted_)
		askForSnapshot();
	uint64_t staleNs = std::max<uint64_t>(kColourStalePeriods * 1'000'000'000u / settings_.colour.fps, kColourStaleMinNs);
	// A tick this late means the loop itself was held (a starved box, a
	// paused VM, a long keying): frames may wait unread in the cameras'
	// queues. The camera is stale only after the loop could watch it for
	// staleNs, so the grace starts again when the loop resumes.
	if (lastFrameTickNs_ != 0 && nowNs - lastFrameTickNs_ > staleNs / 2)
		loopResumedNs_ = nowNs;
	lastFrameTickNs_ = nowNs;
	// A frame with the keying worker is on its way out too, and the
	// pipeline's output, where NO SIGNAL is drawn, is the worker's.
	if (!keyer_.idle())
		return;
	// Frames still held for pairing (pairing.delay_ms) are on their way out:
	// a NO SIGNAL frame now would come between them, out of order.
	if (haveColour_ &&
	    (pairing_.queue().held() > 0 || std::max(lastColourNs_, loopResumedNs_) + staleNs > nowNs))
		return;
	publishNoSignal(nowNs);
}

void Daemon::publishNoSignal(uint64_t nowNs)
{
	noSignal_.fill(colour_ ? colour_->name() : std::string("colour camera"), settings_.colour.width,
		       settings_.colour.height, output_);
	board_.showBoardOnly(); // in board geometry the board's picture goes on, marked offline
	preview_.offer(nullptr, nullptr, nullptr, output_, recordedPictures(nullptr, false), nowNs, nowNs);
	publish(nullptr, nullptr, nowNs, pairing_.depthFresh(nowNs) ? DK_SHM_FLAG_DEPTH_OK : 0);
}

StatusSummary Daemon::summary() const
{
	StatusSummary s;
	s.colourOk = colour_ && colour_->status().state == DeviceState::Streaming;
	s.depthOk = depth_ && depth_->status().state == DeviceState::Streaming;
	s.calibrated = calibrated_ && pipelineStatus_.mappingFits;
	s.error = logger().activeErrorCount() > 0;
	s.boardOk = board_.sourceOk();
	s.boardCalibrated = board_.boardGeometry();
	s.readerAttached = outputs_.readers().total() > 0;
	return s;
}

void Daemon::onReaderTick()
{
	if (outputs_.sampleReaders(loop_.nowUs() * 1000u))
		lights_.show(summary());
}

StatusSnapshot Daemon::statusSnapshot() const
{
	auto camera = [](const auto &device) {
		StatusCamera c;
		if (device) {
			c.present = true;
			c.name = device->name();
			c.status = device->status();
		}
		return c;
	};
	StatusSnapshot s;
	s.colour = camera(colour_);
	s.depth = camera(depth_);
	s.pairing = pairing_.queue().pairer().stats();
	s.latency = pairing_.latency();
	s.offsetAuto = settings_.pairing.offsetAuto;
	s.offset = pairing_.offsetStatus();
	const OffsetGate &gate = pairing_.offsetGate();
	s.offsetApplied = s.offsetAuto && gate.haveApplied();
	s.offsetAppliedMs = gate.appliedMs();
	s.offsetState = !s.offsetAuto ? "set"
		: gate.state() == OffsetGate::State::Applied ? "applied"
		: gate.state() == OffsetGate::State::Held    ? "held"
							     : "measuring";
	s.readers = outputs_.readers();
	s.calibrated = summary().calibrated;
	s.calibrationLoaded = calibrated_;
	s.calibrationFile = settings_.mapping.calibrationFile;
	s.board = board_.statusText();
	s.boardFigures.source = board_.sourceName();
	s.boardFigures.state = deviceStateName(board_.sourceState());
	s.boardFigures.geometry = board_.boardGeometry();
	s.boardFigures.width = board_.outputWidth();
	s.boardFigures.height = board_.outputHeight();
	s.readerEverAttached = outputs_.readerEverAttached();
	s.configPath = configPath_;
	s.webcam = { webcam_.path(), webcam_.status(), webcam_.framesWritten() };
	s.shed = keyer_.dropped();
	s.boardOnly = boardOnlyFrames_;
	s.repeated = outputs_.repeated();
	if (liveScore_.scoring()) {
		s.liveScore = { liveScore_.recent(), liveScore_.sinceStart() };
	}
	return s;
}

void Daemon::onStatusTick()
{
	if (depth_ && depth_->status().state == DeviceState::Streaming) // not measured on lost depth
		pairing_.updateLatency(depth_->name());
	std::optional<PreviewStatus> figures = status_.report(statusSnapshot());
	if (!figures)
		return;
	figures->setup = setup_.update(settings_, calibrationFacts());
	preview_.setStatus(*figures);
	checkCalibrationFits();
	checkRecording();
	lights_.show(summary());
}

void Daemon::apply(const Settings &next, const PipelineFiles &files)
{
	// The pipeline is reconfigured between frames, never under the worker.
	if (!keyer_.idle()) {
		pendingReload_.emplace(next, files);
		return;
	}
	applyNow(next, files);
}

void Daemon::applyNow(const Settings &next, const PipelineFiles &files)
{
	pendingReload_.reset();
	Settings previous = settings_;
	settings_ = next;
	LogLevel level;
	if (parseLogLevel(next.daemon.logLevel, level))
		logger().setLevel(level);
	applyPipelineFiles(files);
	board_.apply(next);
	setup_.invalidate();
	pairing_.configure(settings_);
	stageDumps_.setFolders(next.daemon.snapshotDir, overrides_.previewDir);
	// A new colour size records into a folder of its own (one size a replay).
	if (previous.daemon.recordDir != next.daemon.recordDir ||
	    previous.daemon.recordCompression != next.daemon.recordCompression ||
	    previous.colour.width != next.colour.width || previous.colour.height != next.colour.height)
		updateRecording();

	outputs_.apply(previous, settings_, outputGeometry(), configPath_);
	startWebcam(); // a new output.v4l2_device, or nothing
	if (!(previous.colour == next.colour) || !(previous.depth == next.depth) ||
	    !(previous.sim == next.sim)) {
		stopCameras();
		startCameras();
	}
	if (previous.colour.fps != next.colour.fps)
		loop_.addPeriodic(1000000u / next.colour.fps, [this] { onFrameTick(); }, frameTick_);
	preview_.apply(next.preview);
	lights_.apply(loop_, previous, next);
}

void Daemon::injectTestFault()
{
	if (testFault_ == TestFault::Stall) {
		logger().warning("TEST FAULT: frames stalled, the watchdog is no longer fed",
				 { { "TEST_FAULT", "stall" } });
		keyingStalled_ = true; // the worker wedges at its next frame; the loop goes on
	} else if (testFault_ == TestFault::Hang) {
		logger().warning("TEST FAULT: event loop hanging, the watchdog is no longer fed",
				 { { "TEST_FAULT", "hang" } });
		hangForever();
	}
}

void Daemon::updateRecording()
{
	recorder_.stop();
	const std::string &dir = settings_.daemon.recordDir;
	if (dir.empty())
		return;
	std::string error;
	int ret = recorder_.start(dir, settings_.daemon.recordCompression, error, settings_.colour.width,
				  settings_.colour.height);
	if (ret < 0)
		logger().errorOnce("record", "cannot record: " + error,
				   { { "DEVICE", "recorder" }, { "ERROR", errnoText(ret) } });
	else
		logger().info("recording camera frames to " + recorder_.dir(), { { "RECORD_DIR", recorder_.dir() } });
}

// On the status tick: the worker's write errors and dropped frames.
void Daemon::checkRecording()
{
	if (!recorder_.running())
		return;
	std::string error = recorder_.takeError();
	if (!error.empty())
		logger().errorOnce("record", "recording: " + error, { { "DEVICE", "recorder" } });
	uint64_t dropped = recorder_.dropped();
	if (dropped > recorderDropsLogged_) {
		logger().warning("recording fell behind: " + std::to_string(dropped) + " frames dropped so far",
				 { { "DEVICE", "recorder" } });
		recorderDropsLogged_ = dropped;
	}
}

} // namespace depthkey
