// What the preview page, /status.json and /metrics report. The daemon fills
// it on its status tick (once a second) and hands a copy to the server; the
// server formats it on its own threads.
#pragma once

#include "hal/preview/preview_setup.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace depthkey {

struct PreviewDevice {
	std::string role;        // "colour" or "depth"
	std::string name;        // backend name, e.g. "sim-colour", "sr2"
	std::string state;       // "streaming", "lost", ...
	double fps = 0;
	uint64_t frames = 0;     // delivered
	uint64_t dropped = 0;    // bad frames refused
	uint64_t faults = 0;     // times it was lost
	uint64_t reconnects = 0; // times it streamed again after being lost
};

// The virtual webcam (output.v4l2_device).
struct PreviewWebcam {
	std::string device;      // "" = off
	std::string state = "off"; // "writing", "lost", "off"
	uint64_t frames = 0;     // written
	uint64_t dropped = 0;    // the device took nothing (full): not written
	uint64_t faults = 0;     // times it was lost
	uint64_t reconnects = 0; // times it was written again after being lost
};

// How long keying a frame took since the start (daemon/keying_times.hpp).
struct PreviewKeying {
	uint64_t count = 0;
	uint64_t shed = 0;       // colour frames not keyed: the box was too slow
	double sumS = 0;
	double medianMs = 0, p99Ms = 0, p999Ms = 0, maxMs = 0;
};

// The depth camera's offset (pairing.offset_ms): what was measured, what is
// applied, and in words why not when it is held.
struct PreviewDepthOffset {
	std::string state = "measuring"; // "measuring", "applied", "held", "set"
	std::string text;                // as on the status line
	bool measured = false;
	double measuredMs = 0, correlation = 0;
	bool applied = false;
	double appliedMs = 0;
};

// Issue 29: the published frames scored against their truth (the
// simulator's, a replayed sequence's mask/), over the last 5 s and since
// the start; not scored from a real camera.
struct PreviewLiveScore {
	bool scored = false;
	uint64_t recentFrames = 0;
	double recentIou = 0, recentBoundaryF = 0;
	uint64_t frames = 0;
	double iou = 0, boundaryF = 0;
};

// The board (daemon/board_output.hpp): its source, and whether the output is
// in its geometry.
struct PreviewBoard {
	std::string source;      // backend name, e.g. "sim-board", "colour"
	std::string state;       // "streaming", "lost", ...
	bool geometry = false;   // the composite is in the board's geometry
	int width = 0, height = 0; // the composite's size then
	std::string text;        // as on the status line, with why not calibrated
};

// One of the last distinct error lines (daemon/recent_errors.hpp).
struct PreviewError {
	std::string message;
	double unixTimeS = 0;    // when last logged
	uint64_t count = 1;
};

struct PreviewStatus {
	std::string version;     // DEPTHKEY_VERSION
	std::string configPath;  // the config file the daemon runs on
	double uptimeS = 0;
	std::vector<PreviewDevice> devices;
	double outputFps = 0;
	uint64_t published = 0;          // frames published to shared memory
	PreviewKeying keying;
	uint64_t paired = 0, unpaired = 0;
	uint64_t boardOnly = 0;          // the board's picture alone, after depth first came
	uint64_t repeated = 0;           // capture slots filled with the last output (shed or late)
	uint64_t stale = 0;              // keyed with the nearest depth beyond max_skew_ms
	PreviewLiveScore liveScore;
	bool calibrated = false;
	std::string calibrationFile;
	// Arrival after the depth frame's capture time, always (issue 30: it was
	// the measured offset once there was one, under the same name).
	double depthArrivalMs = 0;
	PreviewDepthOffset depthOffset;
	int readersComposite = 0, readersLecturer = 0, readersBoardLecturer = 0;
	bool readerEverAttached = false; // a recorder read since the start: 0 readers is news then
	PreviewBoard board;
	std::vector<PreviewError> errors; // newest first
	PreviewWebcam webcam;
	PreviewSetup setup; // issue 30: the first-run path's state
	// Filled in by the server when it formats.
	int previewClients = 0;
	uint64_t previewEncoded = 0, previewSkipped = 0;
	double previewEncodeMs = 0;      // mean thread time per JPEG
	// hal/preview/preview_auth.hpp: wrong credentials hashed, requests turned
	// away unchecked (an address backing off, the hashing budget spent),
	// back-offs begun.
	uint64_t previewAuthFailures = 0, previewAuthLimited = 0, previewAuthBlocks = 0;
	uint64_t previewSlowRequestsCut = 0; // connections whose request head was late
};

std::string previewStatusJson(const PreviewStatus &status);
// Prometheus' text exposition format (version 0.0.4).
std::string previewStatusMetrics(const PreviewStatus &status);

} // namespace depthkey
