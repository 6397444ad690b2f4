#include "daemon/status_reporter.hpp"

#include "daemon/log.hpp"
#include "daemon/version.hpp"
#include "hal/v4l2/v4l2_output.hpp"

#include <cstdio>
#include <cstdlib>

namespace depthkey {

namespace {

// In a degraded mode (a camera missing) READY=1 is sent after this long, so
// that systemd's start job does not hang on a box with a camera unplugged.
constexpr uint64_t kDegradedReadyUs = 5'000'000;
constexpr uint64_t kTerminalStatusEvery = 5; // reports (seconds)

} // namespace

void StatusReporter::start(EventLoop &loop)
{
	loop_ = &loop;
	startedUs_ = reportedAtUs_ = loop.nowUs();
	underSystemd_ = std::getenv("NOTIFY_SOCKET") != nullptr;
	if (uint64_t usec = ServiceNotifier::watchdogUsec())
		loop.addPeriodic(usec / 2, [this] { onWatchdogTick(); }, watchdogTick_);
}

void StatusReporter::countDepthFrame(uint64_t captureNs, uint64_t nowNs)
{
	depthFrames_++;
	const double latencyMs = (static_cast<double>(nowNs) - static_cast<double>(captureNs)) / 1e6;
	depthLatencyMs_ += (latencyMs - depthLatencyMs_) * (depthFrames_ == 1 ? 1.0 : 0.1);
}

void StatusReporter::countDeviceStatus(const std::string &device, const DeviceStatus &status)
{
	DeviceCounters &counters = deviceCounters_[device];
	if (status.state == DeviceState::Lost && !counters.lost)
		counters.faults++;
	if (status.state == DeviceState::Streaming && counters.lost)
		counters.reconnects++;
	counters.lost = status.state == DeviceState::Lost;
}

void StatusReporter::countPublished(bool online)
{
	published_++;
	if (!ready_ && online) {
		ready_ = true;
		notifier_.ready();
		logger().info("frames flow, ready");
	}
}

// Fed only while frames are being published: if the frame loop stalls,
// systemd stops hearing from us and restarts the service.
void StatusReporter::onWatchdogTick()
{
	if (published_ == publishedAtWatchdog_)
		return;
	publishedAtWatchdog_ = published_;
	notifier_.watchdog();
}

std::optional<PreviewStatus> StatusReporter::report(const StatusSnapshot &snapshot)
{
	uint64_t now = loop_->nowUs();
	double seconds = (now - reportedAtUs_) / 1e6;
	if (seconds <= 0)
		return std::nullopt;
	auto rate = [seconds](uint64_t count, uint64_t &before) {
		double r = (count - before) / seconds;
		before = count;
		return r;
	};
	Rates rates;
	rates.colourFps = rate(colourFrames_, colourFramesAtReport_);
	rates.depthFps = rate(depthFrames_, depthFramesAtReport_);
	rates.outputFps = rate(published_, publishedAtReport_);
	reportedAtUs_ = now;
	std::string text = statusLine(snapshot, rates);
	notifier_.status(text);
	// In a terminal there is no STATUS= to look at: say it every few seconds.
	if (!underSystemd_ && ++reports_ % kTerminalStatusEvery == 0)
		logger().info(text);
	if (!ready_ && now - startedUs_ > kDegradedReadyUs && published_ > 0) {
		ready_ = true;
		notifier_.ready();
		logger().warning(std::string("ready in degraded mode: ") + text);
	}
	return previewStatus(snapshot, rates);
}

std::string StatusReporter::statusLine(const StatusSnapshot &s, const Rates &rates) const
{
	const DeviceStatus &cs = s.colour.status, &ds = s.depth.status;
	const std::string offset = "depth offset " + s.offset;
	char text[1024];
	std::snprintf(text, sizeof(text),
		      "colour %s %s %.1f fps %llu dropped; depth %s %s %.1f fps %llu dropped; "
		      "paired %llu unpaired %llu stale %llu; %s; output %.1f fps, keying %.1f ms (p99 %.1f), %llu repeated, "
		      "%llu shed; readers %d; %s; %s",
		      s.colour.present ? s.colour.name.c_str() : "-", deviceStateName(cs.state), rates.colourFps,
		      static_cast<unsigned long long>(cs.droppedFrames),
		      s.depth.present ? s.depth.name.c_str() : "-", deviceStateName(ds.state), rates.depthFps,
		      static_cast<unsigned long long>(ds.droppedFrames),
		      static_cast<unsigned long long>(s.pairing.paired),
		      static_cast<unsigned long long>(s.pairing.unpaired),
		      static_cast<unsigned long long>(s.pairing.stale), offset.c_str(), rates.outputFps,
		      double(keying_.quantileUs(0.5)) / 1000.0, double(keying_.quantileUs(0.99)) / 1000.0,
		      static_cast<unsigned long long>(s.repeated), static_cast<unsigned long long>(s.shed), s.readers.total(),
		      s.calibrated		? "calibrated"
		      : s.calibrationLoaded ? "calibration for other frame sizes (identity mapping)"
					    : "not calibrated (identity mapping)",
		      s.board.c_str());
	std::string line = text;
	if (s.liveScore) {
		// The simulator's (or a replay's) truth: what the student sees, scored.
		const LiveScoreFigures &r = s.liveScore->recent, &a = s.liveScore->sinceStart;
		char live[160];
		std::snprintf(live, sizeof(live), "; live IoU %.3f BF %.3f (5 s), %.3f %.3f over %llu frames, %llu board-only",
			      r.iou, r.boundaryF, a.iou, a.boundaryF, static_cast<unsigned long long>(a.frames),
			      static_cast<unsigned long long>(s.boardOnly));
		line += live;
	}
	if (s.webcam.device.empty())
		return line;
	char webcam[256];
	std::snprintf(webcam, sizeof(webcam), "; webcam %s %s %llu dropped", s.webcam.device.c_str(),
		      v4l2OutputStateName(s.webcam.status.state),
		      static_cast<unsigned long long>(s.webcam.status.droppedFrames));
	return line + webcam;
}

// What the preview page (/status.json, /metrics) shows: the figures of the
// STATUS= line and the counters only the page shows.
PreviewStatus StatusReporter::previewStatus(const StatusSnapshot &snapshot, const Rates &rates) const
{
	PreviewStatus s;
	s.version = DEPTHKEY_VERSION;
	s.configPath = snapshot.configPath;
	s.board = snapshot.boardFigures;
	s.board.text = snapshot.board;
	s.readerEverAttached = snapshot.readerEverAttached;
	s.keying.shed = snapshot.shed;
	for (const RecentError &e : logger().recentErrors().list())
		s.errors.push_back({ e.message, static_cast<double>(e.realtimeNs) / 1e9, e.count });
	s.uptimeS = static_cast<double>(loop_->nowUs() - startedUs_) / 1e6;
	s.devices.push_back(previewDevice("colour", snapshot.colour, rates.colourFps, colourFrames_));
	s.devices.push_back(previewDevice("depth", snapshot.depth, rates.depthFps, depthFrames_));
	s.outputFps = rates.outputFps;
	s.published = published_;
	s.keying.count = keying_.count();
	s.keying.sumS = double(keying_.sumUs()) / 1e6;
	s.keying.medianMs = double(keying_.quantileUs(0.5)) / 1000.0;
	s.keying.p99Ms = double(keying_.quantileUs(0.99)) / 1000.0;
	s.keying.p999Ms = double(keying_.quantileUs(0.999)) / 1000.0;
	s.keying.maxMs = double(keying_.maxUs()) / 1000.0;
	s.boardOnly = snapshot.boardOnly;
	s.repeated = snapshot.repeated;
	s.stale = snapshot.pairing.stale;
	if (snapshot.liveScore) {
		const LiveScoreFigures &r = snapshot.liveScore->recent, &a = snapshot.liveScore->sinceStart;
		s.liveScore = { true, r.frames, r.iou, r.boundaryF, a.frames, a.iou, a.boundaryF };
	}
	s.paired = snapshot.pairing.paired;
	s.unpaired = snapshot.pairing.unpaired;
	s.calibrated = snapshot.calibrated;
	s.calibrationFile = snapshot.calibrationFile;
	// How long depth frames take to arrive after their stamp; the offset
	// measured between the cameras' clocks is depth_offset, beside it.
	s.depthArrivalMs = depthLatencyMs_;
	s.depthOffset.state = snapshot.offsetState;
	s.depthOffset.text = snapshot.offset;
	s.depthOffset.measured = snapshot.latency.valid;
	s.depthOffset.measuredMs = snapshot.latency.offsetMs;
	s.depthOffset.correlation = snapshot.latency.correlation;
	s.depthOffset.applied = snapshot.offsetApplied;
	s.depthOffset.appliedMs = snapshot.offsetAppliedMs;
	s.readersComposite = snapshot.readers.composite;
	s.readersLecturer = snapshot.readers.lecturer;
	s.readersBoardLecturer = snapshot.readers.boardLecturer;
	s.webcam.device = snapshot.webcam.device;
	s.webcam.state = v4l2OutputStateName(snapshot.webcam.status.state);
	s.webcam.frames = snapshot.webcam.written;
	s.webcam.dropped = snapshot.webcam.status.droppedFrames;
	if (auto it = deviceCounters_.find("v4l2-output"); it != deviceCounters_.end()) {
		s.webcam.faults = it->second.faults;
		s.webcam.reconnects = it->second.reconnects;
	}
	return s;
}

PreviewDevice StatusReporter::previewDevice(const char *role, const StatusCamera &camera, double fps,
					    uint64_t frames) const
{
	PreviewDevice d;
	d.role = role;
	if (camera.present) {
		d.name = camera.name;
		d.state = deviceStateName(camera.status.state);
		d.dropped = camera.status.droppedFrames;
		auto it = deviceCounters_.find(d.name);
		if (it != deviceCounters_.end()) {
			d.faults = it->second.faults;
			d.reconnects = it->second.reconnects;
		}
	}
	d.fps = fps;
	d.frames = frames;
	return d;
}

} // namespace depthkey
