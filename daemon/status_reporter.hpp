// What depthkeyd tells about itself: the frame and device counters, the
// STATUS= line once a second (and, in a terminal without systemd, the same
// line every few seconds), READY=1 when frames flow (or, with a camera
// missing, after a grace period), the watchdog fed while frames are being
// published, and the figures of the live preview page.
#pragma once

#include "algo/frame_pairer.hpp"
#include "algo/latency_estimator.hpp"
#include "algo/live_score.hpp"
#include "daemon/keying_times.hpp"
#include "daemon/service_notifier.hpp"
#include "hal/camera.hpp"
#include "hal/event_loop.hpp"
#include "hal/frame_sink.hpp"
#include "hal/preview/preview_status.hpp"

#include <cstdint>
#include <map>
#include <optional>
#include <string>

namespace depthkey {

// A camera as the status line names it.
struct StatusCamera {
	bool present = false; // false before the cameras start
	std::string name;
	DeviceStatus status;
};

// The virtual webcam (output.v4l2_device) as the status line names it.
struct StatusWebcam {
	std::string device; // "" = off
	DeviceStatus status;
	uint64_t written = 0;
};

// What the daemon knows once a second that the status line says.
struct StatusSnapshot {
	StatusCamera colour, depth;
	PairingStats pairing;
	LatencyEstimator::Estimate latency; // the depth offset measured
	bool offsetAuto = false;            // pairing.offset_ms = "auto": applied once trusted
	std::string offset;                 // FramePairing::offsetStatus(): measured, applied or held and why
	std::string offsetState;            // "measuring", "applied", "held" or "set"
	bool offsetApplied = false;         // an offset measured here is applied
	double offsetAppliedMs = 0;
	ReaderCounts readers;
	bool calibrated = false;            // a calibration that fits the frames
	bool calibrationLoaded = false;     // a calibration, maybe for other frame sizes
	std::string calibrationFile;
	std::string board;                  // BoardOutput::statusText()
	PreviewBoard boardFigures;          // the same for the preview page (text left to board)
	bool readerEverAttached = false;    // a recorder read since the start
	std::string configPath;
	StatusWebcam webcam;
	uint64_t shed = 0;                  // colour frames not keyed: the box is too slow
	uint64_t boardOnly = 0;             // the board's picture alone, after depth first came
	uint64_t repeated = 0;              // capture slots filled with the last output (shed or late)
	// Issue 29: the published frames against their truth; absent without one.
	struct LiveScores {
		LiveScoreFigures recent, sinceStart;
	};
	std::optional<LiveScores> liveScore;
};

class StatusReporter
{
public:
	// Notes the start time and whether systemd listens, and feeds the
	// watchdog every half WATCHDOG_USEC while frames are published.
	void start(EventLoop &loop);

	void countColourFrame() { colourFrames_++; }
	// The depth frame's arrival after its capture time is smoothed for the
	// preview page.
	void countDepthFrame(uint64_t captureNs, uint64_t nowNs);
	// Faults and reconnects per device, for the preview page.
	void countDeviceStatus(const std::string &device, const DeviceStatus &status);
	// A frame went out; the first online one (both cameras) sends READY=1.
	void countPublished(bool online);
	// How long a colour frame took from the pairing queue to its publication.
	void countKeying(uint64_t us) { keying_.add(us); }
	uint64_t colourFrames() const { return colourFrames_; }

	// Once a second: the status line to systemd, to the terminal every
	// few calls, READY=1 in degraded mode; returns the preview page's
	// figures, or nothing when no time has passed since the last report.
	std::optional<PreviewStatus> report(const StatusSnapshot &snapshot);

	void reloading() { notifier_.reloading(); }
	void reloaded() { notifier_.reloaded(); }
	void stopping() { notifier_.stopping(); }

private:
	struct Rates {
		double colourFps = 0, depthFps = 0, outputFps = 0;
	};
	struct DeviceCounters {
		uint64_t faults = 0, reconnects = 0;
		bool lost = false;
	};
	std::string statusLine(const StatusSnapshot &snapshot, const Rates &rates) const;
	PreviewStatus previewStatus(const StatusSnapshot &snapshot, const Rates &rates) const;
	PreviewDevice previewDevice(const char *role, const StatusCamera &camera, double fps, uint64_t frames) const;
	void onWatchdogTick();

	EventLoop *loop_ = nullptr;
	ServiceNotifier notifier_;
	EventSource watchdogTick_;
	bool ready_ = false;
	bool underSystemd_ = false;
	uint64_t startedUs_ = 0;
	uint64_t reports_ = 0;
	uint64_t colourFrames_ = 0, depthFrames_ = 0, published_ = 0;
	KeyingTimes keying_;
	uint64_t colourFramesAtReport_ = 0, depthFramesAtReport_ = 0, publishedAtReport_ = 0;
	uint64_t reportedAtUs_ = 0;
	uint64_t publishedAtWatchdog_ = 0;
	double depthLatencyMs_ = 0; // smoothed arrival after capture
	std::map<std::string, DeviceCounters> deviceCounters_;
};

} // namespace depthkey
