// What the preview server's tests share, the unit test
// (tests/preview_server_test.cpp) and the fuzz harness
// (tests/fuzz/preview_request_fuzz.cpp): small pictures of every stage to
// feed the encoder, and the client's side of a connection.
#pragma once

#include "algo/image.hpp"
#include "algo/stage_images.hpp"
#include "hal/preview/preview_stages.hpp"

#include <arpa/inet.h>
#include <chrono>
#include <cstdlib>
#include <netinet/in.h>
#include <poll.h>
#include <string>
#include <sys/socket.h>
#include <unistd.h>

namespace depthkey::test {

struct PreviewTestPictures {
	RgbImage rgb{ 32, 24, Rgb8{ 40, 90, 160 } };
	Gray16Image depth{ 16, 12, 1500 };
	Gray8Image gray{ 32, 24, 128 };
	// In PreviewStage order; they point into this object, which is why it
	// is neither copied nor moved.
	const StageImage images[kPreviewStageCount] = {
		{ "colour", StageKind::Colour, &rgb },
		{ "depth", StageKind::Depth, nullptr, &depth },
		{ "seeds", StageKind::Seeds, nullptr, nullptr, &gray },
		{ "alpha", StageKind::Mask, nullptr, nullptr, &gray },
		{ "composite", StageKind::Colour, &rgb },
		{ "lecturer", StageKind::Colour, &rgb },
		{ "board", StageKind::Colour, &rgb },
	};

	PreviewTestPictures() = default;
	PreviewTestPictures(const PreviewTestPictures &) = delete;
	PreviewTestPictures &operator=(const PreviewTestPictures &) = delete;
};

// A connection to the server on 127.0.0.1:port, or -1; from the loopback
// address `from` when given (any of 127.0.0.0/8 is this host: a second
// client address for tests of per-address limits).
inline int connectToPreview(int port, const char *from = nullptr)
{
	const int fd = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
	if (fd < 0)
		return -1;
	if (from) {
		sockaddr_in source{};
		source.sin_family = AF_INET;
		inet_pton(AF_INET, from, &source.sin_addr);
		if (bind(fd, reinterpret_cast<sockaddr *>(&source), sizeof(source)) != 0) {
			close(fd);
			return -1;
		}
	}
	sockaddr_in address{};
	address.sin_family = AF_INET;
	address.sin_port = htons(uint16_t(port));
	address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
	if (connect(fd, reinterpret_cast<sockaddr *>(&address), sizeof(address)) != 0) {
		close(fd);
		return -1;
	}
	return fd;
}

// The answer read until the server closes, a stream has sent its first JPEG
// (the part's end marker after the boundary: streams never end by
// themselves), or the timeout passes.
inline std::string readPreviewReply(int fd, std::chrono::milliseconds timeout)
{
	std::string reply;
	char buffer[4096];
	const auto deadline = std::chrono::steady_clock::now() + timeout;
	for (;;) {
		const auto left =
			std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
		pollfd p{ fd, POLLIN, 0 };
		if (left.count() <= 0 || poll(&p, 1, int(left.count())) <= 0)
			break;
		const ssize_t n = recv(fd, buffer, sizeof(buffer), 0);
		if (n <= 0)
			break;
		reply.append(buffer, size_t(n));
		const size_t part = reply.find("\r\n--boundarydonotcross\r\n");
		if (part != std::string::npos && reply.find("\xff\xd9\r\n", part) != std::string::npos)
			break;
	}
	return reply;
}

// The value of a metric without labels in /metrics text, -1 if absent.
inline double previewMetric(const std::string &text, const std::string &name)
{
	const size_t at = text.find("\n" + name + " ");
	return at == std::string::npos ? -1 : std::atof(text.c_str() + at + name.size() + 2);
}

} // namespace depthkey::test
