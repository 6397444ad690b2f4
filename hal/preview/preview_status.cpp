#include "hal/preview/preview_status.hpp"

#include <cstdio>
#include <nlohmann/json.hpp>

namespace depthkey {

std::string previewStatusJson(const PreviewStatus &s)
{
	nlohmann::json devices = nlohmann::json::array();
	for (const PreviewDevice &d : s.devices)
		devices.push_back({ { "role", d.role },
				    { "name", d.name },
				    { "state", d.state },
				    { "fps", d.fps },
				    { "frames", d.frames },
				    { "dropped", d.dropped },
				    { "faults", d.faults },
				    { "reconnects", d.reconnects } });
	nlohmann::json errors = nlohmann::json::array();
	for (const PreviewError &e : s.errors)
		errors.push_back({ { "message", e.message }, { "unix_time_s", e.unixTimeS }, { "count", e.count } });
	nlohmann::json j = {
		{ "version", s.version },
		{ "config_path", s.configPath },
		{ "uptime_s", s.uptimeS },
		{ "devices", devices },
		{ "output", { { "fps", s.outputFps }, { "frames", s.published }, { "board_only", s.boardOnly },
				{ "repeated", s.repeated } } },
		{ "pairing", { { "paired", s.paired }, { "unpaired", s.unpaired }, { "stale", s.stale } } },
		{ "keying",
		  { { "frames", s.keying.count },
		    { "shed", s.keying.shed },
		    { "median_ms", s.keying.medianMs },
		    { "p99_ms", s.keying.p99Ms },
		    { "p999_ms", s.keying.p999Ms },
		    { "max_ms", s.keying.maxMs } } },
		{ "calibration", { { "calibrated", s.calibrated }, { "file", s.calibrationFile } } },
		{ "depth_arrival_ms", s.depthArrivalMs },
		{ "depth_offset",
		  { { "state", s.depthOffset.state },
		    { "text", s.depthOffset.text },
		    { "measured_ms", s.depthOffset.measured ? nlohmann::json(s.depthOffset.measuredMs) : nlohmann::json() },
		    { "correlation", s.depthOffset.correlation },
		    { "applied_ms", s.depthOffset.applied ? nlohmann::json(s.depthOffset.appliedMs) : nlohmann::json() } } },
		{ "readers", { { "composite", s.readersComposite }, { "lecturer", s.readersLecturer },
				  { "board_lecturer", s.readersBoardLecturer }, { "ever_attached", s.readerEverAttached } } },
		{ "board",
		  { { "source", s.board.source },
		    { "state", s.board.state },
		    { "geometry", s.board.geometry },
		    { "width", s.board.width },
		    { "height", s.board.height },
		    { "text", s.board.text } } },
		{ "errors", errors },
		{ "webcam",
		  { { "device", s.webcam.device },
		    { "state", s.webcam.state },
		    { "frames", s.webcam.frames },
		    { "dropped", s.webcam.dropped },
		    { "faults", s.webcam.faults },
		    { "reconnects", s.webcam.reconnects } } },
		{ "preview",
		  { { "clients", s.previewClients },
		    { "encoded", s.previewEncoded },
		    { "skipped", s.previewSkipped },
		    { "encode_ms", s.previewEncodeMs },
		    { "auth_failures", s.previewAuthFailures },
		    { "auth_limited", s.previewAuthLimited },
		    { "auth_blocks", s.previewAuthBlocks },
		    { "slow_requests_cut", s.previewSlowRequestsCut } } },
	};
	j["setup"] = previewSetupJson(s.setup);
	if (s.liveScore.scored)
		j["live_score"] = { { "recent", { { "window_s", 5 },
						  { "frames", s.liveScore.recentFrames },
						  { "iou", s.liveScore.recentIou },
						  { "bf", s.liveScore.recentBoundaryF } } },
				    { "since_start", { { "frames", s.liveScore.frames },
						       { "iou", s.liveScore.iou },
						       { "bf", s.liveScore.boundaryF } } } };
	// Names come from config and devices: replace anything not UTF-8.
	return j.dump(1, '\t', false, nlohmann::json::error_handler_t::replace) + "\n";
}

namespace {

// A label value per the exposition format: \, " and newline escaped.
std::string labelValue(const std::string &text)
{
	std::string out;
	for (char c : text) {
		if (c == '\\' || c == '"')
			out += '\\';
		if (c == '\n') {
			out += "\\n";
			continue;
		}
		out += c;
	}
	return out;
}

class Exposition
{
public:
	void family(const char *name, const char *type, const char *help)
	{
		text_ += std::string("# HELP ") + name + " " + help + "\n# TYPE " + name + " " + type + "\n";
	}
	void sample(const char *name, const std::string &labels, double value)
	{
		char number[64];
		std::snprintf(number, sizeof(number), "%.17g", value);
		text_ += name;
		if (!labels.empty())
			text_ += "{" + labels + "}";
		text_ += std::string(" ") + number + "\n";
	}
	std::string text_;
};

} // namespace

std::string previewStatusMetrics(const PreviewStatus &s)
{
	Exposition e;
	auto perDevice = [&](const char *name, const char *type, const char *help, auto value) {
		e.family(name, type, help);
		for (const PreviewDevice &d : s.devices)
			e.sample(name, "device=\"" + labelValue(d.role) + "\",name=\"" + labelValue(d.name) + "\"",
				 static_cast<double>(value(d)));
	};
	perDevice("depthkey_device_frames_total", "counter", "Frames a camera delivered.",
		  [](const PreviewDevice &d) { return d.frames; });
	perDevice("depthkey_device_dropped_frames_total", "counter", "Bad frames refused.",
		  [](const PreviewDevice &d) { return d.dropped; });
	perDevice("depthkey_device_faults_total", "counter", "Times a camera was lost.",
		  [](const PreviewDevice &d) { return d.faults; });
	perDevice("depthkey_device_reconnects_total", "counter", "Times a lost camera streamed again.",
		  [](const PreviewDevice &d) { return d.reconnects; });
	perDevice("depthkey_device_fps", "gauge", "Frames per second over the last second.",
		  [](const PreviewDevice &d) { return d.fps; });
	perDevice("depthkey_device_up", "gauge", "1 while the camera streams.",
		  [](const PreviewDevice &d) { return d.state == "streaming" ? 1 : 0; });
	e.family("depthkey_output_frames_total", "counter", "Frames published to shared memory.");
	e.sample("depthkey_output_frames_total", "", static_cast<double>(s.published));
	e.family("depthkey_output_fps", "gauge", "Frames published per second.");
	e.sample("depthkey_output_fps", "", s.outputFps);
	e.family("depthkey_keying_seconds", "summary",
		 "Time from a colour frame leaving the pairing queue to its publication, since the start.");
	e.sample("depthkey_keying_seconds", "quantile=\"0.5\"", s.keying.medianMs / 1000.0);
	e.sample("depthkey_keying_seconds", "quantile=\"0.99\"", s.keying.p99Ms / 1000.0);
	e.sample("depthkey_keying_seconds", "quantile=\"0.999\"", s.keying.p999Ms / 1000.0);
	e.sample("depthkey_keying_seconds_sum", "", s.keying.sumS);
	e.sample("depthkey_keying_seconds_count", "", static_cast<double>(s.keying.count));
	e.family("depthkey_keying_shed_frames_total", "counter",
		 "Colour frames not keyed because the box was too slow (the last frame out was repeated).");
	e.sample("depthkey_keying_shed_frames_total", "", static_cast<double>(s.keying.shed));
	e.family("depthkey_keying_max_seconds", "gauge", "The longest keying of a frame since the start.");
	e.sample("depthkey_keying_max_seconds", "", s.keying.maxMs / 1000.0);
	e.family("depthkey_board_only_frames_total", "counter",
		 "Frames that showed the board's picture alone after depth first came.");
	e.sample("depthkey_board_only_frames_total", "", static_cast<double>(s.boardOnly));
	if (s.liveScore.scored) {
		e.family("depthkey_live_iou", "gauge", "Published lecturer layer against the truth: mean IoU per frame.");
		e.sample("depthkey_live_iou", "window=\"5s\"", s.liveScore.recentIou);
		e.sample("depthkey_live_iou", "window=\"start\"", s.liveScore.iou);
		e.family("depthkey_live_boundary_f", "gauge",
			 "Published lecturer layer against the truth: mean boundary F (2 px) per frame.");
		e.sample("depthkey_live_boundary_f", "window=\"5s\"", s.liveScore.recentBoundaryF);
		e.sample("depthkey_live_boundary_f", "window=\"start\"", s.liveScore.boundaryF);
		e.family("depthkey_live_scored_frames_total", "counter", "Published frames scored against a truth.");
		e.sample("depthkey_live_scored_frames_total", "", static_cast<double>(s.liveScore.frames));
	}
	e.family("depthkey_paired_frames_total", "counter", "Colour frames keyed with a depth frame.");
	e.sample("depthkey_paired_frames_total", "", static_cast<double>(s.paired));
	e.family("depthkey_unpaired_frames_total", "counter", "Colour frames without a depth frame near in time.");
	e.sample("depthkey_unpaired_frames_total", "", static_cast<double>(s.unpaired));
	e.family("depthkey_stale_frames_total", "counter",
		 "Colour frames keyed with the nearest depth frame beyond pairing.max_skew_ms.");
	e.sample("depthkey_stale_frames_total", "", static_cast<double>(s.stale));
	e.family("depthkey_repeated_frames_total", "counter",
		 "Capture slots filled with the last output, flagged repeated (a frame shed or keyed late).");
	e.sample("depthkey_repeated_frames_total", "", static_cast<double>(s.repeated));
	e.family("depthkey_depth_latency_seconds", "gauge", "Depth frame arrival after its capture time.");
	e.sample("depthkey_depth_latency_seconds", "", s.depthArrivalMs / 1000.0);
	e.family("depthkey_depth_offset_measured_seconds", "gauge",
		 "The depth camera's clock offset measured here (pairing.offset_ms); absent until measured.");
	if (s.depthOffset.measured)
		e.sample("depthkey_depth_offset_measured_seconds", "", s.depthOffset.measuredMs / 1000.0);
	e.family("depthkey_depth_offset_applied_seconds", "gauge",
		 "The measured depth offset the pairing applies; absent while none is applied.");
	if (s.depthOffset.applied)
		e.sample("depthkey_depth_offset_applied_seconds", "", s.depthOffset.appliedMs / 1000.0);
	e.family("depthkey_depth_offset_held", "gauge", "1 while a measured offset is held back (not trusted).");
	e.sample("depthkey_depth_offset_held", "", s.depthOffset.state == "held" ? 1 : 0);
	e.family("depthkey_board_geometry", "gauge", "1 when the composite is in the board's geometry (calibrated).");
	e.sample("depthkey_board_geometry", "", s.board.geometry ? 1 : 0);
	e.family("depthkey_board_up", "gauge", "1 while the board's picture source streams.");
	e.sample("depthkey_board_up", "source=\"" + labelValue(s.board.source) + "\"", s.board.state == "streaming" ? 1 : 0);
	e.family("depthkey_info", "gauge", "The daemon's version and config file, as labels.");
	e.sample("depthkey_info", "version=\"" + labelValue(s.version) + "\",config=\"" + labelValue(s.configPath) + "\"", 1);
	e.family("depthkey_recent_errors", "gauge", "Distinct error lines among the last logged (at most 8).");
	e.sample("depthkey_recent_errors", "", static_cast<double>(s.errors.size()));
	e.family("depthkey_calibrated", "gauge", "1 when a calibration fitting the cameras is loaded.");
	e.sample("depthkey_calibrated", "", s.calibrated ? 1 : 0);
	e.family("depthkey_readers", "gauge", "Readers of a shared-memory stream (heartbeats).");
	e.sample("depthkey_readers", "stream=\"composite\"", s.readersComposite);
	e.sample("depthkey_readers", "stream=\"lecturer\"", s.readersLecturer);
	e.sample("depthkey_readers", "stream=\"lecturer.board\"", s.readersBoardLecturer);
	if (!s.webcam.device.empty()) {
		const std::string label = "device=\"" + labelValue(s.webcam.device) + "\"";
		e.family("depthkey_webcam_frames_total", "counter", "Frames written to the virtual webcam.");
		e.sample("depthkey_webcam_frames_total", label, static_cast<double>(s.webcam.frames));
		e.family("depthkey_webcam_dropped_frames_total", "counter",
			 "Frames the virtual webcam's device could not take.");
		e.sample("depthkey_webcam_dropped_frames_total", label, static_cast<double>(s.webcam.dropped));
		e.family("depthkey_webcam_faults_total", "counter", "Times the virtual webcam's device was lost.");
		e.sample("depthkey_webcam_faults_total", label, static_cast<double>(s.webcam.faults));
		e.family("depthkey_webcam_up", "gauge", "1 while frames are written to the virtual webcam.");
		e.sample("depthkey_webcam_up", label, s.webcam.state == "writing" ? 1 : 0);
	}
	e.family("depthkey_preview_clients", "gauge", "Preview streams being sent.");
	e.sample("depthkey_preview_clients", "", s.previewClients);
	e.family("depthkey_preview_jpegs_total", "counter", "Preview JPEGs encoded.");
	e.sample("depthkey_preview_jpegs_total", "", static_cast<double>(s.previewEncoded));
	e.family("depthkey_preview_auth_failures_total", "counter",
		 "Preview requests whose password was checked and wrong.");
	e.sample("depthkey_preview_auth_failures_total", "", static_cast<double>(s.previewAuthFailures));
	e.family("depthkey_preview_auth_limited_total", "counter",
		 "Preview requests turned away unchecked (429): their address backing off after wrong passwords, "
		 "or the hashing budget spent.");
	e.sample("depthkey_preview_auth_limited_total", "", static_cast<double>(s.previewAuthLimited));
	e.family("depthkey_preview_auth_blocks_total", "counter",
		 "Back-offs begun: a client address reached its limit of wrong passwords.");
	e.sample("depthkey_preview_auth_blocks_total", "", static_cast<double>(s.previewAuthBlocks));
	e.family("depthkey_preview_slow_requests_cut_total", "counter",
		 "Preview connections cut because their request head was not whole within 5 s.");
	e.sample("depthkey_preview_slow_requests_cut_total", "", static_cast<double>(s.previewSlowRequestsCut));
	e.family("depthkey_uptime_seconds", "gauge", "Seconds since depthkeyd started.");
	e.sample("depthkey_uptime_seconds", "", s.uptimeS);
	return e.text_;
}

} // namespace depthkey
