// The preview page of the real depthkeyd, fetched with curl: the page, three
// decodable JPEGs of a stream, the status fields, /metrics; clients that stop
// reading do not slow the frame rate; a wrong or missing password is
// refused; a password file others can read or an address off loopback
// without one is refused clearly while the daemon runs on. The server binds
// an ephemeral port (listen = "127.0.0.1:0"), read from the daemon's log.
#include "hal/depthkey_shm.h"
#include "daemon/version.hpp"
#include "hal/v4l2/mjpeg_decoder.hpp"
#include "tests/process/daemon_process.hpp"
#include "tests/process/preview_test_util.hpp"
#include "tests/wait_until.hpp"
#include "tests/shm_test_util.hpp"

#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <crypt.h>
#include <netinet/in.h>
#include <nlohmann/json.hpp>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <thread>
#include <vector>

using namespace std::chrono_literals;
using depthkey::test::curlGet;
using depthkey::test::DaemonProcess;
using depthkey::test::mjpegParts;

namespace {

class PreviewDaemon : public ::testing::Test
{
protected:
	void SetUp() override { prefix_ = "/depthkey-pv-" + std::to_string(getpid()); }
	void TearDown() override
	{
		depthkey::test::unlinkStreams(prefix_);
	}

	std::string config(const std::string &preview) const
	{
		return "[colour]\nwidth = 320\nheight = 240\n[output]\ncomposite_name = \"" + prefix_ +
		       ".composite\"\nlecturer_name = \"" + prefix_ + ".lecturer\"\n[preview]\n" + preview;
	}

	// Starts the daemon and returns the preview's base URL ("" on failure).
	std::string start(const std::string &preview)
	{
		const std::string path = daemon_.writeFile("depthkey.toml", config(preview));
		if (!daemon_.start({ "--config", path }) || !daemon_.waitForNotify("READY=1", 10s))
			return "";
		return depthkey::test::previewUrlFromLog(daemon_.log());
	}

	uint64_t latestFrame() { return depthkey::test::latestSharedFrame(prefix_ + ".composite"); }

	DaemonProcess daemon_;
	std::string prefix_;
};

// Asks for a stream and never reads it.
int stalledClient(const std::string &url, const std::string &path)
{
	int port = std::stoi(url.substr(url.rfind(':') + 1));
	int fd = socket(AF_INET, SOCK_STREAM, 0);
	int small = 4096;
	setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &small, sizeof(small));
	sockaddr_in a{};
	a.sin_family = AF_INET;
	a.sin_port = htons(static_cast<uint16_t>(port));
	inet_pton(AF_INET, "127.0.0.1", &a.sin_addr);
	if (connect(fd, reinterpret_cast<sockaddr *>(&a), sizeof(a)) != 0)
		return -1;
	const std::string request = "GET " + path + " HTTP/1.1\r\nHost: x\r\n\r\n";
	send(fd, request.data(), request.size(), 0);
	return fd;
}

} // namespace

TEST_F(PreviewDaemon, PageStreamStatusAndMetrics)
{
	const std::string url = start("listen = \"127.0.0.1:0\"\n");
	ASSERT_FALSE(url.empty()) << daemon_.log();

	depthkey::test::HttpReply page = curlGet(url + "/");
	EXPECT_EQ(page.code, 200);
	EXPECT_NE(page.body.find("<title>depthkey preview</title>"), std::string::npos);
	EXPECT_NE(page.body.find("data-src=\"/snapshot/composite.jpg\""), std::string::npos);

	depthkey::test::HttpReply stream = curlGet(url + "/stream/composite.mjpg", "--max-time 2");
	EXPECT_EQ(stream.code, 200);
	std::vector<std::string> parts = mjpegParts(stream.body);
	ASSERT_GE(parts.size(), 3u);
	depthkey::MjpegDecoder decoder;
	for (size_t i = 0; i < 3; i++) {
		depthkey::RgbImage rgb;
		EXPECT_EQ(decoder.decode(reinterpret_cast<const uint8_t *>(parts[i].data()), parts[i].size(), 320, 240,
					 rgb),
			  0)
			<< "part " << i << ": " << decoder.lastError();
	}
	// Depth is the ToF image, enlarged 4x to be seen.
	std::vector<std::string> depth = mjpegParts(curlGet(url + "/stream/depth.mjpg", "--max-time 1.5").body);
	ASSERT_GE(depth.size(), 1u);
	depthkey::RgbImage rgb;
	EXPECT_EQ(decoder.decode(reinterpret_cast<const uint8_t *>(depth[0].data()), depth[0].size(), 640, 496, rgb), 0)
		<< decoder.lastError();

	std::this_thread::sleep_for(1200ms); // one status tick after the streams
	depthkey::test::HttpReply status = curlGet(url + "/status.json");
	ASSERT_EQ(status.code, 200);
	EXPECT_EQ(status.contentType, "application/json");
	nlohmann::json j = nlohmann::json::parse(status.body);
	// The depth latency is measured from motion once 30 depth frames are
	// in (pairing.offset_ms = "auto"); in a sanitizer build's first seconds
	// (one in several runs) the first estimate landed at -39 ms before it
	// settled at the simulator's +40. The status is polled until the estimate
	// has had 8 s more. So is the colour rate: under ASan the MJPEG streams
	// just read slow the loop (CI saw 5.9 fps in the status window that
	// held them), and it recovers once they end.
	auto colourFps = [&] { return j["devices"].size() == 2u ? j["devices"][0]["fps"].get<double>() : 0.0; };
	std::vector<double> latencies{ j["depth_arrival_ms"].get<double>() }, rates{ colourFps() };
	depthkey::test::waitUntil(
		[&] {
			if (latencies.back() > 0.0 && rates.back() > 10.0)
				return true;
			status = curlGet(url + "/status.json");
			if (status.code != 200)
				return true; // asserted below
			j = nlohmann::json::parse(status.body);
			latencies.push_back(j["depth_arrival_ms"].get<double>());
			rates.push_back(colourFps());
			return latencies.back() > 0.0 && rates.back() > 10.0;
		},
		8s, 1s);
	ASSERT_EQ(status.code, 200);
	ASSERT_EQ(j["devices"].size(), 2u);
	EXPECT_EQ(j["devices"][0]["role"], "colour");
	EXPECT_EQ(j["devices"][0]["name"], "sim-colour");
	EXPECT_EQ(j["devices"][0]["state"], "streaming");
	// Under the sanitizers the two timing figures (the colour rate and the
	// latency measured from motion) are printed, not judged: the simulated
	// cameras render on the daemon's loop, which ASan slows 2-5 times, so
	// both measure the build and the host's load more than the daemon. A
	// fresh-clone .ci/run at 2483563 saw 8.8-10.6 fps and a latency
	// settled at -25 ms; the same build with two busy loops beside it saw
	// 3-8 fps and estimates wandering from +93 to -35 ms. The plain build's
	// process-check (make test) judges both.
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
	constexpr bool kJudgeTiming = false;
#else
	constexpr bool kJudgeTiming = true;
#endif
	std::printf("    colour fps seen %s, depth latency %s ms%s\n", testing::PrintToString(rates).c_str(),
		    testing::PrintToString(latencies).c_str(), kJudgeTiming ? "" : " (not judged under a sanitizer)");
	if (kJudgeTiming) {
		EXPECT_GT(j["devices"][0]["fps"].get<double>(), 10.0) << "colour fps seen " << testing::PrintToString(rates);
	}
	EXPECT_EQ(j["devices"][1]["name"], "sim-depth");
	EXPECT_GT(j["devices"][1]["frames"].get<int>(), 0);
	EXPECT_GT(j["output"]["frames"].get<int>(), 25);
	EXPECT_GT(j["pairing"]["paired"].get<int>(), 0);
	EXPECT_EQ(j["calibration"]["calibrated"], false);
	if (kJudgeTiming) {
		EXPECT_GT(latencies.back(), 0.0) << "depth latency " << testing::PrintToString(latencies) << " ms";
	}
	EXPECT_EQ(j["readers"]["composite"], 0);
	EXPECT_EQ(j["readers"]["ever_attached"], false) << "no recorder yet: not a fault (issue 30)";
	// Issue 30: the board, the version, the config, the shed frames, the last errors.
	EXPECT_EQ(j["board"]["source"], "sim-board");
	EXPECT_EQ(j["board"]["geometry"], false);
	EXPECT_NE(j["board"]["text"].get<std::string>().find("board not calibrated"), std::string::npos);
	EXPECT_EQ(j["version"], DEPTHKEY_VERSION);
	EXPECT_EQ(j["config_path"].get<std::string>().substr(0, 1), "/");
	EXPECT_TRUE(j["keying"]["shed"].is_number());
	EXPECT_TRUE(j["errors"].is_array());
	EXPECT_GT(j["preview"]["encoded"].get<int>(), 3);
	// Issue 29: the simulated colour camera's truth scores what went out.
	ASSERT_TRUE(j.contains("live_score")) << status.body;
	EXPECT_GT(j["live_score"]["since_start"]["frames"].get<int>(), 0);
	// Far from nothing, at most perfect: a figure computed, not copied. Not
	// more: a few seconds in, the colour models are still being learned and
	// a loaded machine keys few frames (0.43 seen in a fresh-clone make test
	// at load 5; LiveScoreDaemon's test says the same).
	EXPECT_GT(j["live_score"]["since_start"]["iou"].get<double>(), 0.2);
	EXPECT_LE(j["live_score"]["since_start"]["iou"].get<double>(), 1.0);
	EXPECT_GT(j["live_score"]["recent"]["frames"].get<int>(), 0);

	depthkey::test::HttpReply metrics = curlGet(url + "/metrics");
	EXPECT_EQ(metrics.code, 200);
	EXPECT_EQ(metrics.contentType, "text/plain; version=0.0.4; charset=utf-8");
	const std::string framesKey = "\ndepthkey_device_frames_total{device=\"colour\",name=\"sim-colour\"} ";
	const size_t framesAt = metrics.body.find(framesKey);
	ASSERT_NE(framesAt, std::string::npos) << metrics.body;
	const char firstDigit = metrics.body[framesAt + framesKey.size()];
	EXPECT_TRUE(firstDigit >= '1' && firstDigit <= '9') << metrics.body;
	EXPECT_NE(metrics.body.find("# TYPE depthkey_device_reconnects_total counter"), std::string::npos);
	EXPECT_NE(metrics.body.find("depthkey_readers{stream=\"lecturer\"} 0"), std::string::npos);
	EXPECT_NE(metrics.body.find("\ndepthkey_live_iou{window=\"5s\"} 0."), std::string::npos) << metrics.body;
}

// Keyed frames' composite is made only in the shared memory (camera
// geometry: from its parts in the slot); the preview's snapshot must still
// get one, made on the loop once asked. It answered 503 "no composite frame
// yet" for good: the loop told the preview of no composite, so the preview
// never asked (found in a screenshot, 7 December).
TEST_F(PreviewDaemon, TheCompositeMadeOnlyInSharedMemoryIsStillShown)
{
	const std::string url = start("listen = \"127.0.0.1:0\"\n");
	ASSERT_FALSE(url.empty()) << daemon_.log();
	// Past the preview's 2 s window of the NO SIGNAL frames before the
	// cameras ran, whose composite is an image here.
	ASSERT_TRUE(depthkey::test::waitUntil([&] { return latestFrame() > 10; }, 10s)) << daemon_.log();
	std::this_thread::sleep_for(2500ms);
	depthkey::test::HttpReply snapshot = curlGet(url + "/snapshot/composite.jpg", "--max-time 5");
	ASSERT_EQ(snapshot.code, 200) << snapshot.body;
	depthkey::RgbImage rgb;
	depthkey::MjpegDecoder decoder;
	EXPECT_EQ(decoder.decode(reinterpret_cast<const uint8_t *>(snapshot.body.data()), snapshot.body.size(), 320,
				 240, rgb),
		  0)
		<< decoder.lastError();
}

TEST_F(PreviewDaemon, ClientsThatStopReadingDoNotSlowTheFrameRate)
{
	const std::string url = start("listen = \"127.0.0.1:0\"\n");
	ASSERT_FALSE(url.empty()) << daemon_.log();
	// The rate is compared with the daemon's own just before, so that a
	// machine busy with other work does not decide the test.
	auto publishedFps = [this] {
		const uint64_t before = latestFrame();
		const auto t0 = std::chrono::steady_clock::now();
		std::this_thread::sleep_for(3s);
		const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
		return static_cast<double>(latestFrame() - before) / seconds;
	};
	const double alone = publishedFps();
	std::vector<int> stalled;
	for (const char *stage : { "composite", "colour", "alpha" })
		stalled.push_back(stalledClient(url, std::string("/stream/") + stage + ".mjpg"));
	std::this_thread::sleep_for(1500ms); // their socket buffers are full by now
	const double fps = publishedFps();
	EXPECT_GE(fps, 0.8 * alone) << "alone " << alone << " fps, with three clients that stopped reading " << fps;
	// The floor keeps the comparison above from passing on a daemon that
	// did not run; ThreadSanitizer's build runs at 2-3 fps here.
#if defined(__SANITIZE_THREAD__)
	constexpr double kLeastFps = 1.0;
#else
	constexpr double kLeastFps = 5.0;
#endif
	EXPECT_GT(alone, kLeastFps) << "the daemon hardly ran";
	// The stalled clients are still connected and a new one is served.
	EXPECT_EQ(mjpegParts(curlGet(url + "/stream/composite.mjpg", "--max-time 1").body).empty(), false);
	for (int fd : stalled)
		close(fd);
}

TEST_F(PreviewDaemon, WrongOrMissingPasswordIsRefused)
{
	char salt[CRYPT_GENSALT_OUTPUT_SIZE];
	ASSERT_NE(crypt_gensalt_rn("$y$", 0, nullptr, 0, salt, sizeof(salt)), nullptr);
	crypt_data data{};
	const std::string file = daemon_.writeFile("preview.passwd", std::string("tech:") + crypt_r("chalk", salt, &data) + "\n");
	chmod(file.c_str(), 0600);
	const std::string url = start("listen = \"127.0.0.1:0\"\npassword_file = \"" + file + "\"\n");
	ASSERT_FALSE(url.empty()) << daemon_.log();
	EXPECT_NE(daemon_.log().find("(basic authentication)"), std::string::npos);
	EXPECT_EQ(curlGet(url + "/").code, 401);
	EXPECT_EQ(curlGet(url + "/stream/composite.mjpg", "--max-time 1").code, 401);
	EXPECT_EQ(curlGet(url + "/status.json", "-u tech:board").code, 401);
	EXPECT_EQ(curlGet(url + "/metrics", "-u admin:chalk").code, 401);
	EXPECT_EQ(curlGet(url + "/status.json", "-u tech:chalk").code, 200);
}

TEST_F(PreviewDaemon, APasswordFileOthersCanReadIsRefusedAndTheDaemonRunsOn)
{
	const std::string file = daemon_.writeFile("preview.passwd", "tech:$y$j9T$abc$def\n");
	chmod(file.c_str(), 0644);
	const std::string path = daemon_.writeFile(
		"depthkey.toml", config("listen = \"127.0.0.1:0\"\npassword_file = \"" + file + "\"\n"));
	ASSERT_TRUE(daemon_.start({ "--config", path }));
	ASSERT_TRUE(daemon_.waitForNotify("READY=1", 10s)) << daemon_.log();
	EXPECT_NE(daemon_.log().find("preview server not started: " + file +
				     ": mode 0644 lets other users read or change the password hashes; chmod 600 it"),
		  std::string::npos)
		<< daemon_.log();
	EXPECT_EQ(daemon_.log().find("preview page at"), std::string::npos);
	const uint64_t before = latestFrame();
	depthkey::test::waitUntil([&] { return latestFrame() > before; }, 5s);
	EXPECT_GT(latestFrame(), before) << "frames go on without the preview";
}

TEST_F(PreviewDaemon, AnAddressOffLoopbackWithoutPasswordIsAConfigError)
{
	const std::string path = daemon_.writeFile("depthkey.toml", config("listen = \"0.0.0.0:8080\"\n"));
	ASSERT_TRUE(daemon_.start({ "--check-config", path }));
	int status = daemon_.waitExit(5s);
	ASSERT_TRUE(WIFEXITED(status));
	EXPECT_EQ(WEXITSTATUS(status), 1);
	EXPECT_NE(daemon_.log().find("preview.listen: '0.0.0.0:8080' is reachable from the network: set "
				     "preview.password_file"),
		  std::string::npos)
		<< daemon_.log();
}
