// The preview server in-process, fed with synthetic frames: MJPEG parts that
// decode to what was offered, snapshots, the stream limit, basic auth, and a
// client that stops reading never slows the feeding side.
#include "hal/preview/preview_encoder.hpp"
#include "hal/preview/preview_server.hpp"
#include "hal/v4l2/mjpeg_decoder.hpp"
#include "tests/process/preview_test_util.hpp"

#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <atomic>
#include <crypt.h>
#include <fstream>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <thread>

using namespace depthkey;
using namespace std::chrono_literals;
using depthkey::test::curlGet;
using depthkey::test::mjpegParts;

namespace {

constexpr int kW = 320, kH = 240;

uint64_t monotonicNs()
{
	return static_cast<uint64_t>(std::chrono::duration_cast<std::chrono::nanoseconds>(
					     std::chrono::steady_clock::now().time_since_epoch())
					     .count());
}

// Offers a flat colour composite at about 100 Hz, as the event loop would,
// and records the longest offer.
class Feeder
{
public:
	explicit Feeder(PreviewEncoder &encoder) : encoder_(encoder)
	{
		image_.resize(kW, kH);
		thread_ = std::thread([this] {
			while (!stop_) {
				std::fill(image_.data(), image_.data() + image_.size(), Rgb8{ 200, 40, 90 });
				uint64_t t0 = monotonicNs();
				encoder_.made(PreviewStage::Composite, t0);
				if (encoder_.wanted(PreviewStage::Composite, t0))
					encoder_.offer(PreviewStage::Composite, { "", StageKind::Colour, &image_ }, t0, t0);
				uint64_t took = monotonicNs() - t0;
				if (took > longestNs_)
					longestNs_ = took;
				offers_++;
				std::this_thread::sleep_for(10ms);
			}
		});
	}
	~Feeder()
	{
		stop_ = true;
		thread_.join();
	}
	uint64_t longestNs() const { return longestNs_; }
	uint64_t offers() const { return offers_; }

private:
	PreviewEncoder &encoder_;
	RgbImage image_;
	std::atomic<bool> stop_{ false };
	std::atomic<uint64_t> longestNs_{ 0 }, offers_{ 0 };
	std::thread thread_;
};

class PreviewServerTest : public ::testing::Test
{
protected:
	void start(const std::string &passwordFile = "", int maxClients = 4)
	{
		encoder_.start(80, 60);
		PreviewServerOptions options;
		ASSERT_EQ(parseListenAddress("127.0.0.1:0", options.address), "");
		options.passwordFile = passwordFile;
		options.maxClients = maxClients;
		std::string error;
		ASSERT_EQ(server_.start(options, encoder_, error), 0) << error;
		ASSERT_GT(server_.port(), 0);
		url_ = "http://127.0.0.1:" + std::to_string(server_.port());
	}
	void TearDown() override
	{
		server_.stop();
		encoder_.stop();
	}

	PreviewEncoder encoder_;
	PreviewServer server_;
	std::string url_;
};

} // namespace

TEST_F(PreviewServerTest, StreamPartsDecodeToTheOfferedPicture)
{
	start();
	Feeder feeder(encoder_);
	test::HttpReply reply = curlGet(url_ + "/stream/composite.mjpg", "--max-time 1.5");
	EXPECT_EQ(reply.code, 200);
	EXPECT_EQ(reply.contentType, "multipart/x-mixed-replace;boundary=boundarydonotcross");
	std::vector<std::string> parts = mjpegParts(reply.body);
	ASSERT_GE(parts.size(), 3u) << reply.body.size() << " bytes";
	MjpegDecoder decoder;
	for (size_t i = 0; i < 3; i++) {
		RgbImage rgb;
		ASSERT_EQ(decoder.decode(reinterpret_cast<const uint8_t *>(parts[i].data()), parts[i].size(), kW, kH, rgb), 0)
			<< decoder.lastError();
		Rgb8 p = rgb.at(kW / 2, kH / 2);
		EXPECT_NEAR(p.r, 200, 6);
		EXPECT_NEAR(p.g, 40, 6);
		EXPECT_NEAR(p.b, 90, 6);
	}
	// The server notices the closed socket at its next write.
	for (int i = 0; i < 40 && encoder_.watchers(PreviewStage::Composite) > 0; i++)
		std::this_thread::sleep_for(50ms);
	EXPECT_EQ(encoder_.watchers(PreviewStage::Composite), 0) << "the stream's watch ended with it";
}

TEST_F(PreviewServerTest, SnapshotPageAndErrors)
{
	start();
	Feeder feeder(encoder_);
	test::HttpReply snap = curlGet(url_ + "/snapshot/composite.jpg");
	EXPECT_EQ(snap.code, 200);
	EXPECT_EQ(snap.contentType, "image/jpeg");
	MjpegDecoder decoder;
	RgbImage rgb;
	EXPECT_EQ(decoder.decode(reinterpret_cast<const uint8_t *>(snap.body.data()), snap.body.size(), kW, kH, rgb), 0);

	test::HttpReply page = curlGet(url_ + "/");
	EXPECT_EQ(page.code, 200);
	EXPECT_EQ(page.contentType, "text/html; charset=utf-8");
	// Each tile fetches its stage's next JPEG (issue 30: seven endless
	// MJPEG streams took every connection a browser opens to one host).
	for (const char *stage : { "composite", "lecturer", "board", "colour", "depth", "seeds", "alpha" })
		EXPECT_NE(page.body.find(std::string("data-src=\"/snapshot/") + stage + ".jpg\""), std::string::npos) << stage;
	EXPECT_EQ(page.body.find("http://"), std::string::npos) << "nothing from outside the box";
	EXPECT_EQ(page.body.find("https://"), std::string::npos);

	EXPECT_EQ(curlGet(url_ + "/stream/nothing.mjpg").code, 404);
	// No colour picture is made: said at once, and why (not after 3 s).
	const test::HttpReply colour = curlGet(url_ + "/snapshot/colour.jpg");
	EXPECT_EQ(colour.code, 503) << "no colour frame was offered";
	EXPECT_EQ(colour.body.rfind("no colour frame yet: the daemon makes none now", 0), 0u) << colour.body;
	EXPECT_EQ(curlGet(url_ + "/status.json", "-X POST").code, 405);
}

TEST_F(PreviewServerTest, StreamsAreBounded)
{
	start("", 1);
	Feeder feeder(encoder_);
	std::thread first([this] { curlGet(url_ + "/stream/composite.mjpg", "--max-time 2"); });
	std::this_thread::sleep_for(500ms);
	test::HttpReply second = curlGet(url_ + "/stream/composite.mjpg", "--max-time 1");
	first.join();
	EXPECT_EQ(second.code, 503);
	EXPECT_NE(second.body.find("preview.max_clients = 1"), std::string::npos) << second.body;
}

TEST_F(PreviewServerTest, AClientThatStopsReadingNeverSlowsTheFeeder)
{
	start();
	Feeder feeder(encoder_);
	// A client that asks for the stream and never reads: its socket fills,
	// its thread blocks in send, and only it misses frames.
	int fd = socket(AF_INET, SOCK_STREAM, 0);
	int small = 4096;
	setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &small, sizeof(small));
	sockaddr_in a{};
	a.sin_family = AF_INET;
	a.sin_port = htons(static_cast<uint16_t>(server_.port()));
	inet_pton(AF_INET, "127.0.0.1", &a.sin_addr);
	ASSERT_EQ(connect(fd, reinterpret_cast<sockaddr *>(&a), sizeof(a)), 0);
	const std::string request = "GET /stream/composite.mjpg HTTP/1.1\r\nHost: x\r\n\r\n";
	ASSERT_EQ(send(fd, request.data(), request.size(), 0), static_cast<ssize_t>(request.size()));
	std::this_thread::sleep_for(1500ms); // long enough to fill both socket buffers

	// Meanwhile a reading client gets fresh frames, and the feeder's offers
	// stayed short.
	const uint64_t encodedBefore = encoder_.stats().encoded;
	const uint64_t offersBefore = feeder.offers();
	std::vector<std::string> parts = mjpegParts(curlGet(url_ + "/stream/composite.mjpg", "--max-time 1").body);
	EXPECT_GE(parts.size(), 5u);
	EXPECT_GT(encoder_.stats().encoded, encodedBefore + 5);
	EXPECT_GE(feeder.offers() - offersBefore, 50u) << "the feeder (100 Hz) was held up";
	EXPECT_LT(feeder.longestNs(), 20'000'000u) << "an offer took " << feeder.longestNs() / 1e6 << " ms";
	close(fd);
}

TEST_F(PreviewServerTest, BasicAuthRefusesMissingAndWrongPasswords)
{
	char salt[CRYPT_GENSALT_OUTPUT_SIZE];
	ASSERT_NE(crypt_gensalt_rn("$y$", 0, nullptr, 0, salt, sizeof(salt)), nullptr);
	crypt_data data{};
	const std::string path = "/tmp/depthkey-preview-passwd-" + std::to_string(getpid());
	std::ofstream(path) << "tech:" << crypt_r("board", salt, &data) << "\n";
	chmod(path.c_str(), 0600);
	start(path);
	test::HttpReply missing = curlGet(url_ + "/status.json");
	EXPECT_EQ(missing.code, 401);
	EXPECT_EQ(curlGet(url_ + "/status.json", "-u tech:chalk").code, 401);
	EXPECT_EQ(curlGet(url_ + "/stream/composite.mjpg", "-u other:board --max-time 1").code, 401);
	EXPECT_EQ(curlGet(url_ + "/status.json", "-u tech:board").code, 200);
	EXPECT_EQ(curlGet(url_ + "/status.json", "-u tech:board").code, 200) << "again (cached)";
	EXPECT_EQ(curlGet(url_ + "/status.json", "-u tech:boar").code, 401) << "not a prefix of a cached one";
	unlink(path.c_str());
}

TEST_F(PreviewServerTest, OffLoopbackWithoutPasswordIsRefused)
{
	PreviewServerOptions options;
	ASSERT_EQ(parseListenAddress("0.0.0.0:0", options.address), "");
	std::string error;
	EXPECT_EQ(server_.start(options, encoder_, error), -EPERM);
	EXPECT_NE(error.find("password_file is required"), std::string::npos) << error;
	EXPECT_FALSE(server_.running());
}

TEST(PreviewEncoder, CopiesOnlyWhileSomebodyWaits)
{
	PreviewEncoder encoder;
	encoder.start(80, 25);
	EXPECT_FALSE(encoder.wanted(PreviewStage::Colour, 1'000'000'000u));
	// A client that watches but does not ask (its socket is full) costs
	// nothing.
	encoder.watch(PreviewStage::Colour);
	EXPECT_FALSE(encoder.wanted(PreviewStage::Colour, 1'000'000'000u)) << "watched, nobody waits";
	std::shared_ptr<const EncodedFrame> frame;
	std::thread client([&] { frame = encoder.waitNewer(PreviewStage::Colour, 0, 5s); });
	const auto deadline = std::chrono::steady_clock::now() + 5s;
	while (!encoder.wanted(PreviewStage::Colour, 1'000'000'000u) && std::chrono::steady_clock::now() < deadline)
		std::this_thread::sleep_for(1ms);
	ASSERT_TRUE(encoder.wanted(PreviewStage::Colour, 1'000'000'000u)) << "a client waits";
	RgbImage image(kW, kH, Rgb8{ 10, 20, 30 });
	ASSERT_TRUE(encoder.offer(PreviewStage::Colour, { "", StageKind::Colour, &image }, 5, 1'000'000'000u));
	client.join();
	ASSERT_TRUE(frame);
	EXPECT_EQ(frame->captureNs, 5u);
	EXPECT_EQ(frame->width, kW);
	EXPECT_EQ(frame->height, kH);
	EXPECT_EQ(frame->sequence, 1u);
	EXPECT_FALSE(encoder.wanted(PreviewStage::Colour, 1'040'000'000u)) << "served: nobody waits now";
	EXPECT_TRUE(encoder.waitNewer(PreviewStage::Colour, 0, 0ms)) << "the newest JPEG without waiting";
	// Waiting again asks for a copy, but at most max_fps of them.
	std::thread again([&] { frame = encoder.waitNewer(PreviewStage::Colour, 1, 300ms); });
	while (!encoder.wanted(PreviewStage::Colour, 1'040'000'000u) && std::chrono::steady_clock::now() < deadline)
		std::this_thread::sleep_for(1ms);
	EXPECT_FALSE(encoder.wanted(PreviewStage::Colour, 1'010'000'000u)) << "within 1/25 s of the last copy";
	EXPECT_TRUE(encoder.wanted(PreviewStage::Colour, 1'040'000'000u));
	again.join();
	EXPECT_FALSE(frame) << "no newer frame was offered";
	encoder.unwatch(PreviewStage::Colour);
	EXPECT_FALSE(encoder.wanted(PreviewStage::Colour, 2'000'000'000u));
	// made() is the stage's sign of life, watched or not, for kMakingWindowNs.
	EXPECT_FALSE(encoder.making(PreviewStage::Depth, 2'000'000'000u)) << "never made";
	encoder.made(PreviewStage::Depth, 2'000'000'000u);
	EXPECT_TRUE(encoder.making(PreviewStage::Depth, 2'000'000'000u + PreviewEncoder::kMakingWindowNs - 1));
	EXPECT_TRUE(encoder.making(PreviewStage::Depth, 1'999'000'000u)) << "the caller's clock read just before";
	EXPECT_FALSE(encoder.making(PreviewStage::Depth, 2'000'000'000u + PreviewEncoder::kMakingWindowNs));
	EXPECT_FALSE(encoder.making(PreviewStage::Colour, 2'000'000'000u)) << "one stage's life is not another's";
	encoder.stop();
	EXPECT_FALSE(encoder.wanted(PreviewStage::Colour, 2'000'000'000u));
}
