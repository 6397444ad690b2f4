#include "daemon/daemon.hpp"

#include "algo/composite.hpp"
#include "algo/no_signal_frame.hpp"
#include "config/config_loader.hpp"
#include "daemon/log.hpp"
#include "hal/depthkey_shm.h"
#include "wiring/pipeline_setup.hpp"

#include <csignal>
#include <cstdio>
#include <cmath>

namespace depthkey {

namespace {

// Depth counts as delivering (DEPTH_OK on NO SIGNAL frames) while its newest
// frame is younger than this; pairing itself uses pairing.max_skew_ms.
constexpr int64_t kDepthStaleNs = 500'000'000;
// Without a colour frame for this many frame periods, publish NO SIGNAL.
constexpr uint64_t kColourStalePeriods = 3;
// Reader heartbeats are sampled this often: a dead reader is gone within
// DK_SHM_READER_TIMEOUT_MS plus this.
constexpr uint64_t kReaderTickUs = 250'000;

} // namespace

void CommandLineOverrides::applyTo(Settings &settings) const
{
	if (!snapshotDir.empty())
		settings.daemon.snapshotDir = snapshotDir;
	if (!recordDir.empty())
		settings.daemon.recordDir = recordDir;
}

Daemon::~Daemon()
{
	preview_.stop();
	recorder_.stop();
	stopCameras();
	board_.stop();
	if (sink_)
		sink_->close();
	if (leds_)
		leds_->close();
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
	loop_.addSignal(SIGHUP, [this] { reload(); }, sighup_);
	loop_.addSignal(SIGUSR1, [this] { stageDumps_.writeSnapshot(queue_.pairer().newest(), pipelineView()); },
			sigusr1_);

	status_.start(loop_);
	stageDumps_.setFolders(settings_.daemon.snapshotDir, overrides_.previewDir);
	applyPipelineFiles(loadPipelineFiles(settings_));
	configurePairing();

	leds_ = factory_.statusLeds(settings_);
	if (leds_->open(loop_, settings_.leds) < 0)
		logger().errorOnce("leds", "status LEDs unavailable, running without them",
				   { { "DEVICE", "leds" } });

	board_.start(
		loop_, settings_, factory_.boardSource, pipeline_,
		[this](const std::string &name, const DeviceStatus &s) { onDeviceStatus(name, s); },
		[this] { // the composite's geometry or size changed
			if (sink_) {
				sink_->close();
				openOutput();
			}
		});
	openOutput();
	startWebcam();
	updateRecording();
	preview_.apply(settings_.preview);
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
	preview_.stop();
	stopCameras();
	board_.stop();
	recorder_.stop();
	if (sink_)
		sink_->close();
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
	if (!sink_)
		sink_ = factory_.frameSink(settings_);
	int ret = sink_->open(settings_.output, settings_.colour.width, settings_.colour.height,
			      board_.outputWidth(), board_.outputHeight());
	sinkOpen_ = ret >= 0;
	if (ret < 0)
		logger().errorOnce("output", "cannot open shared-memory output: " + sink_->describeError(),
				   { { "DEVICE", "shm" }, { "ERROR", errnoText(ret) } });
	else
		logger().clearError("output", "shared-memory output open", { { "DEVICE", "shm" } });
	return ret;
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
	queue_.clear();
	keyTimer_.reset();
}

void Daemon::configurePairing()
{
	configurePairingQueue(queue_, settings_, offsetNs());
	latency_.configure(settings_.segmentation.nearMm, settings_.segmentation.farMm);
}

int64_t Daemon::offsetNs() const
{
	if (!settings_.pairing.offsetAuto)
		return int64_t{ settings_.pairing.offsetMs } * 1'000'000;
	return latencyEstimate_.valid ? int64_t(std::llround(latencyEstimate_.offsetMs * 1e6)) : 0;
}

void Daemon::updateLatency()
{
	latencyEstimate_ = latency_.estimate();
	if (!latencyEstimate_.valid)
		return;
	if (settings_.pairing.offsetAuto)
		queue_.setOffset(offsetNs());
	if (std::abs(latencyEstimate_.offsetMs - latencyLoggedMs_) >= 5.0) {
		latencyLoggedMs_ = latencyEstimate_.offsetMs;
		char text[160];
		std::snprintf(text, sizeof(text), "depth offset measured: %+.0f ms (correlation %.2f)%s",
			      latencyEstimate_.offsetMs, latencyEstimate_.correlation,
			      settings_.pairing.offsetAuto ? ", applied" : "; pairing.offset_ms is set, not applied");
		logger().info(text, { { "DEVICE", depth_ ? depth_->name() : std::string("depth") },
				      { "DEPTH_OFFSET_MS", std::to_string(std::lround(latencyEstimate_.offsetMs)) } });
	}
}

void Daemon::onDeviceStatus(const std::string &device, const DeviceStatus &status)
{
	status_.countDeviceStatus(device, status);
	if (status.state == DeviceState::Lost)
		logger().errorOnce(device, device + " lost: " + status.detail,
				   { { "DEVICE", device }, { "ERROR", errnoText(status.error) } });
	else if (status.state == DeviceState::Streaming)
		logger().clearError(device, device + " streaming again", { { "DEVICE", device } });
	if (leds_)
		leds_->show(summary());
}

void Daemon::onDepthFrame(const DepthFrame &frame)
{
	depthWidth_ = frame.depthMm.width();
	depthHeight_ = frame.depthMm.height();
	queue_.addDepth(frame); // same-size copy: no allocation after the first
	latency_.addDepth(frame, frame.timestampNs);
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
	latency_.addColour(frame.rgb, frame.timestampNs);
	queue_.addColour(frame, loop_.nowUs() * 1000u);
	keyDueFrames();
}

void Daemon::keyDueFrames()
{
	const uint64_t nowNs = loop_.nowUs() * 1000u;
	PairingQueue::Keying keying;
	while (queue_.next(nowNs, keying)) {
		keyFrame(keying);
		queue_.pop();
	}
	if (!queue_.held()) {
		keyTimer_.reset();
		return;
	}
	const uint64_t deadlineNs = queue_.nextDeadlineNs();
	const uint64_t waitUs = deadlineNs > nowNs ? (deadlineNs - nowNs + 999) / 1000 : 0;
	loop_.addTimer(waitUs, [this] { keyDueFrames(); }, keyTimer_);
}

void Daemon::keyFrame(const PairingQueue::Keying &keying)
{
	const ColourFrame &frame = *keying.colour;
	uint32_t flags = DK_SHM_FLAG_COLOUR_OK;
	const DepthFrame *depth = keying.depth.before ? keying.depth.before : keying.depth.after;
	if (depth) {
		pipeline_.process(frame, keying.depth, output_);
		flags |= DK_SHM_FLAG_DEPTH_OK | DK_SHM_FLAG_ONLINE;
	} else {
		pipeline_.passThrough(frame, output_);
	}
	// Board geometry: the lecturer warped onto the board's picture. Without
	// depth the board's picture alone goes out, marked offline: it is the
	// lecture's content, and warping the whole colour frame would cost the
	// CPU a slow box needs to get depth back.
	if (depth)
		board_.compose(output_.lecturer, pipeline_.roi(), opacityToQ8(settings_.composite.opacity));
	else
		board_.showBoardOnly();
	stageDumps_.onKeyedFrame(frame, depth, status_.colourFrames(), pipelineView());
	preview_.offer(&frame, depth, depth ? &pipeline_.trimap() : nullptr, output_, frame.timestampNs,
		       loop_.nowUs() * 1000u);
	publish(frame.timestampNs, flags);
}

bool Daemon::depthFresh(uint64_t nowNs) const
{
	int64_t ts;
	if (!queue_.pairer().newestNs(ts))
		return false;
	int64_t d = ts - static_cast<int64_t>(nowNs);
	return d <= kDepthStaleNs && d >= -kDepthStaleNs;
}

void Daemon::publish(uint64_t captureNs, uint32_t flags)
{
	if (framesStalled_)
		return;
	const bool board = board_.boardGeometry();
	// Never waits; a full or lost device is its own status (hal/v4l2/v4l2_output.hpp).
	webcam_.write(board ? board_.composite() : output_.composite);
	if (!sinkOpen_ && openOutput() < 0)
		return;
	int ret = sink_->publishComposite(board ? board_.composite() : output_.composite, captureNs, flags);
	if (ret >= 0)
		ret = sink_->publishLecturer(output_.lecturer, captureNs, flags);
	if (ret >= 0 && board)
		ret = sink_->publishBoardLecturer(board_.lecturer(), captureNs, flags);
	if (ret < 0) {
		logger().errorOnce("output", "cannot publish: " + sink_->describeError(),
				   { { "DEVICE", "shm" }, { "ERROR", errnoText(ret) } });
		return;
	}
	status_.countPublished(flags & DK_SHM_FLAG_ONLINE);
}

// Runs at the colour frame rate: when colour frames stop (camera lost or
// stalled), keep the recorder fed with a NO SIGNAL frame marked offline.
void Daemon::onFrameTick()
{
	uint64_t nowNs = loop_.nowUs() * 1000u;
	uint64_t periodNs = 1'000'000'000u / settings_.colour.fps;
	// Frames still held for pairing (pairing.delay_ms) are on their way out:
	// a NO SIGNAL frame now would come between them, out of order.
	if (haveColour_ && (queue_.held() > 0 || lastColourNs_ + kColourStalePeriods * periodNs > nowNs))
		return;
	publishNoSignal(nowNs);
}

void Daemon::publishNoSignal(uint64_t nowNs)
{
	int w = settings_.colour.width, h = settings_.colour.height;
	std::string text = "NO SIGNAL: " + (colour_ ? colour_->name() : std::string("colour camera"));
	if (noSignal_.width() != w || noSignal_.height() != h || text != noSignalText_) {
		noSignal_.resize(w, h);
		renderNoSignalFrame(text, noSignal_);
		noSignalText_ = text;
	}
	output_.composite = noSignal_;
	output_.alpha.resize(w, h);
	std::fill(output_.alpha.data(), output_.alpha.data() + output_.alpha.size(), 0);
	output_.lecturer.resize(w, h);
	std::fill(output_.lecturer.data(), output_.lecturer.data() + output_.lecturer.size(), Rgba8{ 0, 0, 0, 0 });
	board_.showBoardOnly(); // in board geometry the board's picture goes on, marked offline
	preview_.offer(nullptr, nullptr, nullptr, output_, nowNs, nowNs);
	publish(nowNs, depthFresh(nowNs) ? DK_SHM_FLAG_DEPTH_OK : 0);
}

StatusSummary Daemon::summary() const
{
	StatusSummary s;
	s.colourOk = colour_ && colour_->status().state == DeviceState::Streaming;
	s.depthOk = depth_ && depth_->status().state == DeviceState::Streaming;
	s.calibrated = calibrated_ && pipeline_.status().mappingFits;
	s.error = logger().activeErrorCount() > 0;
	s.boardOk = board_.sourceOk();
	s.boardCalibrated = board_.boardGeometry();
	s.readerAttached = readers_.total() > 0;
	return s;
}

void Daemon::onReaderTick()
{
	if (!sink_ || !sinkOpen_)
		return;
	ReaderCounts now = sink_->countReaders(loop_.nowUs() * 1000u);
	if (now == readers_)
		return;
	bool attachedChanged = (now.total() > 0) != (readers_.total() > 0);
	readers_ = now;
	logger().info("readers: composite " + std::to_string(now.composite) + ", lecturer " +
			      std::to_string(now.lecturer) + ", board-geometry lecturer " +
			      std::to_string(now.boardLecturer),
		      { { "DEVICE", "shm" } });
	if (attachedChanged && leds_)
		leds_->show(summary());
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
	s.pairing = queue_.pairer().stats();
	s.latency = latencyEstimate_;
	s.offsetAuto = settings_.pairing.offsetAuto;
	s.readers = readers_;
	s.calibrated = summary().calibrated;
	s.calibrationLoaded = calibrated_;
	s.calibrationFile = settings_.mapping.calibrationFile;
	s.board = board_.statusText();
	s.webcam = { webcam_.path(), webcam_.status(), webcam_.framesWritten() };
	return s;
}

void Daemon::onStatusTick()
{
	updateLatency();
	std::optional<PreviewStatus> figures = status_.report(statusSnapshot());
	if (!figures)
		return;
	preview_.setStatus(*figures);
	checkCalibrationFits();
	checkRecording();
	if (leds_)
		leds_->show(summary());
}

// Reading and parsing (the config, then the calibration and board image it
// names) run on reloadJob_'s thread: a hostile 1 MiB file takes longer to
// parse than several frame periods (background_job.hpp). The loop thread
// only applies the result. A SIGHUP during a reload is folded into one more
// reload after it.
void Daemon::reload()
{
	if (reloadJob_.running()) {
		reloadAgain_ = true;
		return;
	}
	status_.reloading();
	auto next = std::make_shared<PendingReload>();
	int ret = reloadJob_.start(
		loop_,
		[next, path = configPath_, overrides = overrides_] {
			next->config = loadConfig(path);
			if (next->config.ok()) {
				overrides.applyTo(next->config.settings);
				next->files = loadPipelineFiles(next->config.settings);
			}
		},
		[this, next] { finishReload(*next); });
	if (ret < 0) {
		logger().error("config reload failed: cannot start a worker: " + errnoText(ret),
			       { { "CONFIG_FILE", configPath_ } });
		status_.reloaded();
	}
}

void Daemon::finishReload(const PendingReload &next)
{
	const ConfigResult &result = next.config;
	if (!result.ok()) {
		for (const ConfigError &e : result.errors)
			logger().error("config reload refused: " + e.toString(),
				       { { "CONFIG_FILE", e.file }, { "CONFIG_LINE", std::to_string(e.line) } });
		logger().warning("keeping the previous configuration", { { "CONFIG_FILE", configPath_ } });
	} else {
		apply(result.settings, next.files);
		logger().info("configuration reloaded", { { "CONFIG_FILE", configPath_ } });
	}
	status_.reloaded();
	if (reloadAgain_) {
		reloadAgain_ = false;
		reload();
	}
}

void Daemon::apply(const Settings &next, const PipelineFiles &files)
{
	Settings previous = settings_;
	settings_ = next;
	LogLevel level;
	if (parseLogLevel(next.daemon.logLevel, level))
		logger().setLevel(level);
	applyPipelineFiles(files);
	board_.apply(next);
	configurePairing();
	stageDumps_.setFolders(next.daemon.snapshotDir, overrides_.previewDir);
	if (previous.daemon.recordDir != next.daemon.recordDir ||
	    previous.daemon.recordCompression != next.daemon.recordCompression)
		updateRecording();

	bool sizeChanged = previous.colour.width != next.colour.width ||
			   previous.colour.height != next.colour.height;
	if (!sameSharedMemory(previous.output, next.output) || sizeChanged) {
		sink_->close();
		// An [output] that cannot be opened (a group we may not chgrp to,
		// a name another user holds) must not cost the recorder its stream.
		if (openOutput() < 0 && !sameSharedMemory(previous.output, next.output)) {
			logger().error("output settings not applied: " + sink_->describeError() +
					       "; keeping the previous [output]",
				       { { "DEVICE", "shm" }, { "CONFIG_FILE", configPath_ } });
			settings_.output = previous.output;
			settings_.output.v4l2Device = next.output.v4l2Device;
			openOutput();
		}
	}
	startWebcam(); // a new output.v4l2_device, or nothing
	if (!(previous.colour == next.colour) || !(previous.depth == next.depth) ||
	    !(previous.sim == next.sim)) {
		stopCameras();
		startCameras();
	}
	if (previous.colour.fps != next.colour.fps)
		loop_.addPeriodic(1000000u / next.colour.fps, [this] { onFrameTick(); }, frameTick_);
	preview_.apply(next.preview);
	if (!(previous.leds == next.leds)) {
		leds_->close();
		leds_ = factory_.statusLeds(next);
		leds_->open(loop_, next.leds);
	}
}

void Daemon::injectTestFault()
{
	if (testFault_ == TestFault::Stall) {
		logger().warning("TEST FAULT: frames stalled, the watchdog is no longer fed",
				 { { "TEST_FAULT", "stall" } });
		framesStalled_ = true;
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
	int ret = recorder_.start(dir, settings_.daemon.recordCompression, error);
	if (ret < 0)
		logger().errorOnce("record", "cannot record: " + error,
				   { { "DEVICE", "recorder" }, { "ERROR", errnoText(ret) } });
	else
		logger().info("recording camera frames to " + dir, { { "RECORD_DIR", dir } });
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
