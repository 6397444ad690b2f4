// libFuzzer harness: the preview server's request handling
// (hal/preview/preview_server.hpp), end to end as a misbehaving HTTP client
// meets it: the input is the raw bytes a client sends on a loopback
// connection to a running PreviewServer (libmicrohttpd's parser, then our
// routing, method check and HTTP Basic authentication against a password
// file). The server must answer or close, never crash or hang: the client
// half-closes after its bytes and reads the reply for at most 300 ms
// (streams never end by themselves: once a stream has sent its first JPEG,
// closing our end ends it, rather than waiting out the 300 ms). A feeder
// thread offers a small picture of every stage, so snapshots have frames,
// and answers POST /snapshot as a daemon's loop does.
//
// The password file has one account, fuzz:secret (sha512crypt with the
// fewest rounds crypt allows, 1000: each wrong password costs a hash, and
// the verification code is the same whatever the count); the seed corpus
// carries requests with and without its Authorization header.
#include "config/listen_address.hpp"
#include "hal/preview/preview_encoder.hpp"
#include "hal/preview/preview_server.hpp"
#include "tests/preview_test_support.hpp"

#include <atomic>
#include <cerrno>
#include <chrono>
#include <crypt.h>
#include <cstdio>
#include <cstdlib>
#include <fcntl.h>
#include <string>
#include <sys/socket.h>
#include <sys/stat.h>
#include <thread>
#include <time.h>
#include <unistd.h>

using namespace depthkey;

namespace {

struct Server {
	PreviewEncoder encoder;
	PreviewServer server;
	std::thread feeder;
	std::atomic<bool> stop{ false };
	int port = 0;

	Server()
	{
		char dir[] = "/tmp/depthkey-fuzz-preview-XXXXXX";
		if (!mkdtemp(dir))
			std::abort();
		const std::string passwords = std::string(dir) + "/passwords";
		const char *hash = crypt("secret", "$6$rounds=1000$depthkeyfuzz$");
		if (!hash)
			std::abort();
		FILE *f = std::fopen(passwords.c_str(), "w");
		if (!f)
			std::abort();
		std::fprintf(f, "# the fuzz harness's account\nfuzz:%s\n", hash);
		std::fclose(f);
		chmod(passwords.c_str(), 0600);
		std::string error;
		if (encoder.start(50, 1000) < 0)
			std::abort();
		PreviewServerOptions options;
		if (!parseListenAddress("127.0.0.1:0", options.address).empty())
			std::abort();
		options.passwordFile = passwords;
		options.maxClients = 4;
		// Every wrong password hashed, as before the limits (issue 31): the
		// fuzzer reaches the verification on every input, not a 429.
		options.authLimits.perAddress.maxFailures = 1 << 30;
		options.authLimits.hashesPerSecond = 1e9;
		if (server.start(options, encoder, error) < 0) {
			std::fprintf(stderr, "preview_request_fuzz: %s\n", error.c_str());
			std::abort();
		}
		port = server.port();
		feeder = std::thread([this] { feed(); });
	}
	~Server()
	{
		stop = true;
		feeder.join();
		server.stop();
		encoder.stop();
	}

	// Small pictures of every stage, every 5 ms (offered every millisecond,
	// the encoder thread took a third of the time re-encoding watched stages).
	void feed()
	{
		const test::PreviewTestPictures pictures;
		while (!stop) {
			timespec ts;
			clock_gettime(CLOCK_MONOTONIC, &ts);
			const uint64_t now = uint64_t(ts.tv_sec) * 1000000000u + uint64_t(ts.tv_nsec);
			for (size_t s = 0; s < kPreviewStageCount; ++s)
				encoder.offer(PreviewStage(s), pictures.images[s], now, now);
			// POST /snapshot waits for the loop's answer: give the one a
			// daemon without snapshot_dir gives, at once, as its loop would.
			if (server.snapshots().pending())
				server.snapshots().answer(-ENOENT, "daemon.snapshot_dir is not set");
			std::this_thread::sleep_for(std::chrono::milliseconds(5));
		}
	}
};

Server &server()
{
	static Server s;
	return s;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	const int fd = test::connectToPreview(server().port);
	if (fd < 0)
		return 0;
	// The bytes as sent, then our half closed: the server sees the end.
	size_t sent = 0;
	while (sent < size) {
		const ssize_t n = send(fd, data + sent, size - sent, MSG_NOSIGNAL);
		if (n <= 0)
			break;
		sent += size_t(n);
	}
	shutdown(fd, SHUT_WR);
	test::readPreviewReply(fd, std::chrono::milliseconds(300));
	close(fd);
	return 0;
}
