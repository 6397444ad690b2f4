// /status.json and /metrics from one PreviewStatus: JSON that parses back to
// the same figures, and Prometheus text with HELP/TYPE per family and
// escaped labels.
#include "hal/preview/preview_status.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

using namespace depthkey;

namespace {

PreviewStatus sample()
{
	PreviewStatus s;
	s.uptimeS = 12.5;
	s.devices = { { "colour", "sim-colour", "streaming", 25.0, 300, 1, 0, 0 },
		      { "depth", "sr2 \"usb\"\\1", "lost", 0.0, 90, 4, 2, 1 } };
	s.outputFps = 24.5;
	s.published = 299;
	s.keying = { 299, 7, 1.0465, 3.5, 15.625, 31.25, 62.5 }; // ms that are exact binary fractions in s
	s.paired = 280;
	s.unpaired = 19;
	s.stale = 7;
	s.repeated = 11;
	s.calibrated = true;
	s.calibrationFile = "/var/lib/depthkey/calibration.toml";
	s.depthArrivalMs = 40;
	s.version = "0.1.0";
	s.configPath = "/etc/depthkey/depthkey.toml";
	s.board = { "sim-board", "streaming", true, 1920, 780, "board sim-board streaming, board geometry 1920x780" };
	s.errors = { { "colour camera lost: /dev/video0", 1765000000.5, 3 } };
	s.depthOffset = { "held", "measured -215 ms, none applied, held: 1 of 5 steady estimates", true, -215, 0.88,
			  false, 0 };
	s.readersComposite = 1;
	s.readersBoardLecturer = 2;
	s.previewClients = 2;
	return s;
}

} // namespace

TEST(PreviewStatus, JsonCarriesEveryFigure)
{
	nlohmann::json j = nlohmann::json::parse(previewStatusJson(sample()));
	ASSERT_EQ(j["devices"].size(), 2u);
	EXPECT_EQ(j["devices"][0]["name"], "sim-colour");
	EXPECT_EQ(j["devices"][0]["fps"], 25.0);
	EXPECT_EQ(j["devices"][1]["name"], "sr2 \"usb\"\\1");
	EXPECT_EQ(j["devices"][1]["state"], "lost");
	EXPECT_EQ(j["devices"][1]["faults"], 2);
	EXPECT_EQ(j["devices"][1]["reconnects"], 1);
	EXPECT_EQ(j["devices"][1]["dropped"], 4);
	EXPECT_EQ(j["output"]["frames"], 299);
	EXPECT_EQ(j["keying"]["frames"], 299);
	EXPECT_EQ(j["keying"]["median_ms"], 3.5);
	EXPECT_EQ(j["keying"]["p999_ms"], 31.25);
	EXPECT_EQ(j["keying"]["max_ms"], 62.5);
	EXPECT_EQ(j["pairing"]["paired"], 280);
	EXPECT_EQ(j["pairing"]["unpaired"], 19);
	EXPECT_EQ(j["pairing"]["stale"], 7);
	EXPECT_EQ(j["output"]["repeated"], 11);
	EXPECT_EQ(j["calibration"]["calibrated"], true);
	EXPECT_EQ(j["depth_arrival_ms"], 40.0);
	EXPECT_FALSE(j.contains("depth_latency_ms")) << "one name, one meaning (issue 30)";
	EXPECT_EQ(j["keying"]["shed"], 7);
	EXPECT_EQ(j["version"], "0.1.0");
	EXPECT_EQ(j["config_path"], "/etc/depthkey/depthkey.toml");
	EXPECT_EQ(j["board"]["source"], "sim-board");
	EXPECT_EQ(j["board"]["geometry"], true);
	EXPECT_EQ(j["board"]["width"], 1920);
	EXPECT_EQ(j["board"]["height"], 780);
	ASSERT_EQ(j["errors"].size(), 1u);
	EXPECT_EQ(j["errors"][0]["message"], "colour camera lost: /dev/video0");
	EXPECT_EQ(j["errors"][0]["unix_time_s"], 1765000000.5);
	EXPECT_EQ(j["errors"][0]["count"], 3);
	EXPECT_EQ(j["readers"]["ever_attached"], false);
	EXPECT_EQ(j["depth_offset"]["state"], "held");
	EXPECT_EQ(j["depth_offset"]["measured_ms"], -215.0);
	EXPECT_TRUE(j["depth_offset"]["applied_ms"].is_null()); // held: none applied
	EXPECT_NE(j["depth_offset"]["text"].get<std::string>().find("held: 1 of 5"), std::string::npos);
	EXPECT_EQ(j["readers"]["composite"], 1);
	EXPECT_EQ(j["readers"]["lecturer"], 0);
	EXPECT_EQ(j["readers"]["board_lecturer"], 2);
	EXPECT_EQ(j["preview"]["clients"], 2);
}

TEST(PreviewStatus, MetricsAreInTheExpositionFormat)
{
	const std::string text = previewStatusMetrics(sample());
	EXPECT_NE(text.find("# TYPE depthkey_device_frames_total counter\n"), std::string::npos);
	EXPECT_NE(text.find("depthkey_device_frames_total{device=\"colour\",name=\"sim-colour\"} 300\n"),
		  std::string::npos);
	EXPECT_NE(text.find("depthkey_device_faults_total{device=\"depth\",name=\"sr2 \\\"usb\\\"\\\\1\"} 2\n"),
		  std::string::npos)
		<< text;
	EXPECT_NE(text.find("depthkey_device_up{device=\"depth\",name=\"sr2 \\\"usb\\\"\\\\1\"} 0\n"), std::string::npos);
	EXPECT_NE(text.find("# TYPE depthkey_output_fps gauge\ndepthkey_output_fps 24.5\n"), std::string::npos);
	EXPECT_NE(text.find("# TYPE depthkey_stale_frames_total counter\ndepthkey_stale_frames_total 7\n"),
		  std::string::npos);
	EXPECT_NE(text.find("# TYPE depthkey_repeated_frames_total counter\ndepthkey_repeated_frames_total 11\n"),
		  std::string::npos);
	EXPECT_NE(text.find("# TYPE depthkey_keying_seconds summary\n"), std::string::npos);
	EXPECT_NE(text.find("depthkey_keying_seconds{quantile=\"0.99\"} 0.015625\n"), std::string::npos) << text;
	EXPECT_NE(text.find("depthkey_keying_seconds_count 299\n"), std::string::npos);
	EXPECT_NE(text.find("depthkey_readers{stream=\"composite\"} 1\n"), std::string::npos);
	EXPECT_NE(text.find("depthkey_readers{stream=\"lecturer.board\"} 2\n"), std::string::npos);
	EXPECT_NE(text.find("depthkey_depth_latency_seconds 0.040000000000000001\n"), std::string::npos);
	EXPECT_NE(text.find("depthkey_keying_shed_frames_total 7\n"), std::string::npos) << text;
	EXPECT_NE(text.find("depthkey_depth_offset_measured_seconds -0.215\n"), std::string::npos) << text;
	EXPECT_EQ(text.find("\ndepthkey_depth_offset_applied_seconds "), std::string::npos) << "held: none applied";
	EXPECT_NE(text.find("depthkey_depth_offset_held 1\n"), std::string::npos);
	EXPECT_NE(text.find("depthkey_board_geometry 1\n"), std::string::npos);
	EXPECT_NE(text.find("depthkey_info{version=\"0.1.0\",config=\"/etc/depthkey/depthkey.toml\"} 1\n"),
		  std::string::npos);
	EXPECT_NE(text.find("depthkey_recent_errors 1\n"), std::string::npos);

	// Every sample line belongs to a family declared before it, once.
	std::istringstream lines(text);
	std::string line, family;
	std::set<std::string> declared;
	while (std::getline(lines, line)) {
		ASSERT_FALSE(line.empty());
		if (line.rfind("# TYPE ", 0) == 0) {
			family = line.substr(7, line.find(' ', 7) - 7);
			EXPECT_TRUE(declared.insert(family).second) << family << " declared twice";
		} else if (line[0] != '#') {
			EXPECT_EQ(line.rfind(family, 0), 0u) << line << " outside " << family;
		}
	}
	EXPECT_GE(declared.size(), 15u);
}

TEST(PreviewStatus, TheVirtualWebcamIsReportedWhenConfigured)
{
	PreviewStatus s = sample();
	EXPECT_EQ(previewStatusMetrics(s).find("depthkey_webcam"), std::string::npos) << "off: no webcam series";
	EXPECT_EQ(nlohmann::json::parse(previewStatusJson(s))["webcam"]["state"], "off");
	s.webcam = { "/dev/video10", "lost", 250, 7, 2, 1 };
	nlohmann::json j = nlohmann::json::parse(previewStatusJson(s));
	EXPECT_EQ(j["webcam"]["device"], "/dev/video10");
	EXPECT_EQ(j["webcam"]["state"], "lost");
	EXPECT_EQ(j["webcam"]["frames"], 250);
	EXPECT_EQ(j["webcam"]["dropped"], 7);
	EXPECT_EQ(j["webcam"]["faults"], 2);
	EXPECT_EQ(j["webcam"]["reconnects"], 1);
	const std::string text = previewStatusMetrics(s);
	EXPECT_NE(text.find("depthkey_webcam_frames_total{device=\"/dev/video10\"} 250\n"), std::string::npos) << text;
	EXPECT_NE(text.find("depthkey_webcam_dropped_frames_total{device=\"/dev/video10\"} 7\n"), std::string::npos);
	EXPECT_NE(text.find("depthkey_webcam_up{device=\"/dev/video10\"} 0\n"), std::string::npos);
}

// Issue 29: the live score, when the frames have a truth (the simulator, a
// replayed sequence's mask/); nothing of it from a real camera.
TEST(PreviewStatus, LiveScoreIsReportedOnlyWhenScored)
{
	PreviewStatus s = sample();
	s.boardOnly = 3;
	EXPECT_FALSE(nlohmann::json::parse(previewStatusJson(s)).contains("live_score"));
	EXPECT_EQ(previewStatusMetrics(s).find("depthkey_live_"), std::string::npos);
	s.liveScore = { true, 125, 0.9375, 0.75, 1500, 0.96875, 0.8125 }; // exact binary fractions
	nlohmann::json j = nlohmann::json::parse(previewStatusJson(s));
	EXPECT_EQ(j["output"]["board_only"], 3);
	EXPECT_EQ(j["live_score"]["recent"]["window_s"], 5);
	EXPECT_EQ(j["live_score"]["recent"]["frames"], 125);
	EXPECT_EQ(j["live_score"]["recent"]["iou"], 0.9375);
	EXPECT_EQ(j["live_score"]["recent"]["bf"], 0.75);
	EXPECT_EQ(j["live_score"]["since_start"]["frames"], 1500);
	EXPECT_EQ(j["live_score"]["since_start"]["iou"], 0.96875);
	EXPECT_EQ(j["live_score"]["since_start"]["bf"], 0.8125);
	const std::string text = previewStatusMetrics(s);
	EXPECT_NE(text.find("depthkey_live_iou{window=\"5s\"} 0.9375\n"), std::string::npos) << text;
	EXPECT_NE(text.find("depthkey_live_iou{window=\"start\"} 0.96875\n"), std::string::npos);
	EXPECT_NE(text.find("depthkey_live_boundary_f{window=\"5s\"} 0.75\n"), std::string::npos);
	EXPECT_NE(text.find("depthkey_live_boundary_f{window=\"start\"} 0.8125\n"), std::string::npos);
	EXPECT_NE(text.find("depthkey_live_scored_frames_total 1500\n"), std::string::npos);
	EXPECT_NE(text.find("depthkey_board_only_frames_total 3\n"), std::string::npos);
}
