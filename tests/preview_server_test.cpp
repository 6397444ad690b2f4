// The preview's HTTP server in-process (hal/preview/preview_server.hpp): a
// real PreviewServer on loopback, a PreviewEncoder fed as the event loop
// feeds it (only the stages somebody waits for), and clients on threads of
// their own. The process tests (tests/process/preview_daemon_test.cpp) drive
// it through the daemon; here it runs inside the unit suite, so that
// `make SAN=thread check` sees its threads (libmicrohttpd's, the encoder's,
// the feeder's, the status setter's) meet: the server's status copy, its
// cache of verified passwords, the stream count, the encoder's slots.
#include "config/listen_address.hpp"
#include "hal/preview/preview_encoder.hpp"
#include "hal/preview/preview_server.hpp"
#include "tests/joined_thread.hpp"
#include "tests/preview_test_support.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <crypt.h>
#include <cstdio>
#include <string>
#include <sys/socket.h>
#include <sys/stat.h>
#include <thread>
#include <time.h>
#include <unistd.h>
#include <vector>

using namespace depthkey;

namespace {

uint64_t nowNs()
{
	timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return uint64_t(ts.tv_sec) * 1000000000u + uint64_t(ts.tv_nsec);
}

// The password file's account: "teacher", password "chalk".
constexpr const char *kAuth = "Authorization: Basic dGVhY2hlcjpjaGFsaw==\r\n";
constexpr const char *kWrongAuth = "Authorization: Basic dGVhY2hlcjpjaGVlc2U=\r\n"; // teacher:cheese

// A server with a password file, an encoder, and a feeder thread that offers
// every stage somebody waits for, every 5 ms, as the daemon's loop does.
class PreviewServerTest : public ::testing::Test
{
protected:
	void SetUp() override
	{
		char dir[] = "/tmp/depthkey-preview-server-test-XXXXXX";
		ASSERT_NE(mkdtemp(dir), nullptr);
		dir_ = dir;
		passwords_ = dir_ + "/passwords";
		// The fewest rounds crypt allows: each wrong password costs a hash.
		const char *hash = crypt("chalk", "$6$rounds=1000$depthkeytest$");
		ASSERT_NE(hash, nullptr);
		FILE *f = std::fopen(passwords_.c_str(), "w");
		ASSERT_NE(f, nullptr);
		std::fprintf(f, "teacher:%s\n", hash);
		std::fclose(f);
		chmod(passwords_.c_str(), 0600);
		ASSERT_EQ(encoder_.start(50, 50), 0);
	}
	void TearDown() override
	{
		stopFeeding();
		server_.stop();
		encoder_.stop();
		unlink(passwords_.c_str());
		rmdir(dir_.c_str());
	}

	void startServer(int maxClients, const MicroHttpd *(*load)(std::string &) = nullptr)
	{
		PreviewServerOptions options;
		options.load = load;
		ASSERT_TRUE(parseListenAddress("127.0.0.1:0", options.address).empty());
		options.passwordFile = passwords_;
		options.maxClients = maxClients;
		std::string error;
		ASSERT_EQ(server_.start(options, encoder_, error), 0) << error;
		ASSERT_GT(server_.port(), 0);
		feeder_ = std::thread([this] { feed(); });
	}
	void stopFeeding()
	{
		stop_ = true;
		if (feeder_.joinable())
			feeder_.join();
	}

	void feed()
	{
		const test::PreviewTestPictures pictures;
		while (!stop_) {
			const uint64_t now = nowNs();
			for (size_t s = 0; s < kPreviewStageCount; ++s) {
				encoder_.made(PreviewStage(s), now);
				if (encoder_.wanted(PreviewStage(s), now))
					encoder_.offer(PreviewStage(s), pictures.images[s], now, now);
			}
			std::this_thread::sleep_for(std::chrono::milliseconds(5));
		}
	}

	// Sends a GET for path (with the header lines given) and reads the
	// answer until the server closes, a stream's first JPEG has come whole,
	// or timeoutMs pass. Keeps the connection open while keepOpen says so
	// (a stream somebody still watches).
	std::string get(const std::string &path, const char *headers = kAuth, int timeoutMs = 3000,
			std::atomic<bool> *keepOpen = nullptr, const char *method = "GET")
	{
		const int fd = test::connectToPreview(server_.port());
		if (fd < 0)
			return "connect failed";
		std::string reply;
		const std::string request =
			std::string(method) + " " + path + " HTTP/1.1\r\nHost: localhost\r\nConnection: close\r\n" + headers + "\r\n";
		if (send(fd, request.data(), request.size(), MSG_NOSIGNAL) == ssize_t(request.size()))
			reply = test::readPreviewReply(fd, std::chrono::milliseconds(timeoutMs));
		while (keepOpen && *keepOpen)
			std::this_thread::sleep_for(std::chrono::milliseconds(5));
		close(fd);
		return reply;
	}

	static int status(const std::string &reply)
	{
		return reply.rfind("HTTP/1.1 ", 0) == 0 ? std::atoi(reply.c_str() + 9) : 0;
	}

	std::string dir_, passwords_;
	PreviewEncoder encoder_;
	PreviewServer server_;
	std::thread feeder_;
	std::atomic<bool> stop_{ false };
};

TEST_F(PreviewServerTest, ServesConcurrentClientsWhileTheStatusChanges)
{
	startServer(8);
	// The daemon's status tick, much faster than once a second.
	std::atomic<bool> ticking{ true };
	std::thread ticker([&] {
		for (int i = 0; ticking; ++i) {
			PreviewStatus s;
			s.uptimeS = i;
			s.published = uint64_t(i);
			s.devices.push_back({ "colour", "sim-colour", "streaming", 25.0, uint64_t(i), 0, 0, 0 });
			server_.setStatus(s);
			std::this_thread::sleep_for(std::chrono::milliseconds(1));
		}
	});
	struct Client {
		std::string path;
		const char *headers;
		int expected;
		std::string mustContain;
	};
	const std::vector<Client> clients = {
		{ "/status.json", kAuth, 200, "\"output\"" },
		{ "/metrics", kAuth, 200, "depthkey_" },
		{ "/", kAuth, 200, "<html" },
		{ "/snapshot/colour.jpg", kAuth, 200, "\xff\xd8" },
		{ "/snapshot/alpha.jpg", kAuth, 200, "\xff\xd8" },
		{ "/stream/depth.mjpg", kAuth, 200, "\xff\xd8" },
		{ "/stream/composite.mjpg", kAuth, 200, "\xff\xd8" },
		{ "/status.json", kWrongAuth, 401, "authentication required" },
		{ "/status.json", "", 401, "authentication required" },
		{ "/nothing", kAuth, 404, "no such page" },
	};
	// Ten threads at once, each its client three times over: within the
	// server's limit per client address (max_clients + 16 = 24), which closes more.
	std::vector<std::string> replies(clients.size() * 3);
	std::vector<std::thread> threads;
	for (size_t c = 0; c < clients.size(); ++c)
		threads.emplace_back([&, c] {
			for (size_t i = c; i < replies.size(); i += clients.size())
				replies[i] = get(clients[c].path, clients[c].headers);
		});
	for (std::thread &t : threads)
		t.join();
	ticking = false;
	ticker.join();
	for (size_t i = 0; i < replies.size(); ++i) {
		const Client &c = clients[i % clients.size()];
		EXPECT_EQ(status(replies[i]), c.expected) << c.path << ": " << replies[i].substr(0, 200);
		EXPECT_NE(replies[i].find(c.mustContain), std::string::npos) << c.path << ": " << replies[i].substr(0, 200);
	}
	EXPECT_GT(encoder_.stats().encoded, 0u);
}

TEST_F(PreviewServerTest, StreamsBeyondMaxClientsAreRefusedUntilOneCloses)
{
	startServer(2);
	std::atomic<bool> watching{ true };
	std::string first, second;
	test::JoinedThread a([&] { watching = false; }, [&] { first = get("/stream/colour.mjpg", kAuth, 3000, &watching); });
	test::JoinedThread b([&] { watching = false; }, [&] { second = get("/stream/alpha.mjpg", kAuth, 3000, &watching); });
	// Both streams counted before the third asks.
	for (int i = 0; i < 300 && server_.streams() < 2; ++i)
		std::this_thread::sleep_for(std::chrono::milliseconds(10));
	ASSERT_EQ(server_.streams(), 2);
	const std::string third = get("/stream/seeds.mjpg");
	EXPECT_EQ(status(third), 503) << third.substr(0, 200);
	EXPECT_NE(third.find("preview.max_clients = 2"), std::string::npos);
	watching = false;
	a.join();
	b.join();
	EXPECT_EQ(status(first), 200);
	EXPECT_EQ(status(second), 200);
	// Their threads see the closed sockets and give the places back.
	for (int i = 0; i < 300 && server_.streams() > 0; ++i)
		std::this_thread::sleep_for(std::chrono::milliseconds(10));
	EXPECT_EQ(server_.streams(), 0);
	const std::string again = get("/stream/seeds.mjpg");
	EXPECT_EQ(status(again), 200) << again.substr(0, 200);
}

TEST_F(PreviewServerTest, StopsPromptlyWithStreamsOpen)
{
	startServer(4);
	std::atomic<bool> watching{ true };
	std::vector<std::thread> viewers;
	for (const char *stage : { "colour", "depth", "composite" })
		viewers.emplace_back([&, stage] { get(std::string("/stream/") + stage + ".mjpg", kAuth, 3000, &watching); });
	for (int i = 0; i < 300 && server_.streams() < 3; ++i)
		std::this_thread::sleep_for(std::chrono::milliseconds(10));
	ASSERT_EQ(server_.streams(), 3);
	const auto before = std::chrono::steady_clock::now();
	server_.stop(); // the daemon's reload or shutdown: viewers still connected
	const auto took = std::chrono::steady_clock::now() - before;
	EXPECT_FALSE(server_.running());
	// A stream waits for a frame at most 500 ms at a time (kStreamWait).
	EXPECT_LT(std::chrono::duration_cast<std::chrono::milliseconds>(took).count(), 2000);
	watching = false;
	for (std::thread &t : viewers)
		t.join();
}

// Loaders that count their calls: the real one, and one that fails as a
// missing library would.
std::atomic<int> loads{ 0 };
const MicroHttpd *countedLoad(std::string &error)
{
	++loads;
	return loadMicroHttpd(error);
}
const MicroHttpd *failingLoad(std::string &error)
{
	++loads;
	error = "cannot load libmicrohttpd.so.12: no such file (test)";
	return nullptr;
}

TEST_F(PreviewServerTest, LoadsLibmicrohttpdOnlyWhenTheFirstClientComes)
{
	loads = 0;
	startServer(4, &countedLoad);
	std::this_thread::sleep_for(std::chrono::milliseconds(50));
	EXPECT_TRUE(server_.running());
	EXPECT_FALSE(server_.serving());
	EXPECT_EQ(loads.load(), 0);
	const std::string first = get("/status.json");
	EXPECT_EQ(status(first), 200) << first.substr(0, 200);
	EXPECT_TRUE(server_.serving());
	EXPECT_EQ(loads.load(), 1);
	const std::string second = get("/metrics");
	EXPECT_EQ(status(second), 200) << second.substr(0, 200);
	EXPECT_EQ(loads.load(), 1);
	EXPECT_EQ(server_.takeError(), "");
}

TEST_F(PreviewServerTest, AClientIsToldWhyWhenTheLibraryCannotBeLoadedAndTheNextTriesAgain)
{
	loads = 0;
	startServer(4, &failingLoad);
	const std::string first = get("/status.json");
	EXPECT_EQ(status(first), 503) << first.substr(0, 200);
	EXPECT_NE(first.find("preview unavailable: cannot load libmicrohttpd.so.12: no such file (test)"),
		  std::string::npos)
		<< first;
	EXPECT_FALSE(server_.serving());
	EXPECT_NE(server_.takeError().find("cannot load libmicrohttpd.so.12"), std::string::npos);
	EXPECT_EQ(server_.takeError(), ""); // once
	const std::string second = get("/");
	EXPECT_EQ(status(second), 503);
	EXPECT_EQ(loads.load(), 2);
	const auto before = std::chrono::steady_clock::now();
	server_.stop();
	EXPECT_LT(std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now() - before)
			  .count(),
		  500);
	EXPECT_FALSE(server_.running());
}

TEST_F(PreviewServerTest, StopsAndRestartsBeforeAnyClient)
{
	loads = 0;
	startServer(4, &countedLoad);
	const int port = server_.port();
	server_.stop();
	EXPECT_FALSE(server_.running());
	// The port is free again: a new server (a reload) can bind it.
	PreviewServerOptions options;
	ASSERT_TRUE(parseListenAddress("127.0.0.1:" + std::to_string(port), options.address).empty());
	options.passwordFile = passwords_;
	options.load = &countedLoad;
	std::string error;
	ASSERT_EQ(server_.start(options, encoder_, error), 0) << error;
	EXPECT_EQ(loads.load(), 0);
	const std::string reply = get("/status.json");
	EXPECT_EQ(status(reply), 200) << reply.substr(0, 200);
	EXPECT_EQ(loads.load(), 1);
}

} // namespace

// Issue 30: the page's snapshot button. POST only, authenticated, with the
// page's header; answered by the daemon's loop (here a thread that answers
// as it would); one at a time, at most one per 2 s.
TEST_F(PreviewServerTest, SnapshotIsAnAuthenticatedPostAnsweredByTheLoopAndRateLimited)
{
	startServer(4);
	const std::string marker = std::string(kAuth) + "X-Depthkey-Snapshot: 1\r\n";
	EXPECT_EQ(status(get("/snapshot", "X-Depthkey-Snapshot: 1\r\n", 3000, nullptr, "POST")), 401);
	EXPECT_EQ(status(get("/snapshot", marker.c_str())), 405) << "a GET must not write files";
	EXPECT_EQ(status(get("/snapshot", kAuth, 3000, nullptr, "POST")), 400) << "a form from another site";
	EXPECT_FALSE(server_.snapshots().pending());

	std::atomic<bool> answering{ true };
	std::atomic<int> answered{ 0 };
	std::thread loop([&] {
		while (answering) {
			if (server_.snapshots().pending()) {
				server_.snapshots().answer(answered == 0 ? 0 : -ENOENT,
							   answered == 0 ? "snapshot written to /tmp/x" : "daemon.snapshot_dir is not set");
				answered++;
			}
			std::this_thread::sleep_for(std::chrono::milliseconds(5));
		}
	});
	const std::string first = get("/snapshot", marker.c_str(), 6000, nullptr, "POST");
	EXPECT_EQ(status(first), 200) << first;
	EXPECT_NE(first.find("snapshot written to /tmp/x"), std::string::npos) << first;
	const std::string again = get("/snapshot", marker.c_str(), 6000, nullptr, "POST");
	EXPECT_EQ(status(again), 429) << again;
	EXPECT_EQ(answered, 1) << "the refused request never reached the loop";
	std::this_thread::sleep_for(std::chrono::milliseconds(2100));
	const std::string unset = get("/snapshot", marker.c_str(), 6000, nullptr, "POST");
	EXPECT_EQ(status(unset), 409) << unset;
	EXPECT_NE(unset.find("snapshot_dir is not set"), std::string::npos) << unset;
	answering = false;
	loop.join();
}
