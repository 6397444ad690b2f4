// Helpers for the preview server tests: curl as the client, and the JPEG
// parts of a multipart MJPEG stream.
#pragma once

#include "hal/depthkey_shm.h"
#include "tests/process/shell_command.hpp"

#include <atomic>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace depthkey::test {

struct HttpReply {
	int code = 0;            // HTTP status, 0 when curl failed
	std::string contentType;
	std::string body;
};

// curl URL with extra options (e.g. "-u tech:secret", "--max-time 2");
// a stream cut by --max-time still returns what arrived.
inline HttpReply curlGet(const std::string &url, const std::string &options = "")
{
	// Atomic: tests call this from several threads at once (a name taken
	// twice would mix two replies; ThreadSanitizer found it).
	static std::atomic<int> counter{ 0 };
	const std::string file = "/tmp/depthkey-curl-" + std::to_string(getpid()) + "-" + std::to_string(counter++);
	int status;
	std::string out = run("curl -s -o " + file + " -w '%{http_code} %{content_type}' " + options + " '" + url + "'",
			      status);
	HttpReply reply;
	std::istringstream head(out);
	head >> reply.code;
	std::getline(head >> std::ws, reply.contentType);
	std::ifstream in(file, std::ios::binary);
	std::stringstream body;
	body << in.rdbuf();
	reply.body = body.str();
	unlink(file.c_str());
	return reply;
}

// The preview's base URL ("http://127.0.0.1:PORT", no slash) from the
// daemon's "preview page at http://127.0.0.1:PORT/" log line, "" if absent.
// (No std::regex: gcc 12 warns inside <regex> under -fsanitize, and the
// build treats warnings as errors.)
inline std::string previewUrlFromLog(const std::string &log)
{
	const std::string key = "preview page at http://127.0.0.1:";
	const size_t at = log.find(key);
	if (at == std::string::npos)
		return "";
	size_t end = at + key.size();
	while (end < log.size() && log[end] >= '0' && log[end] <= '9')
		end++;
	if (end == at + key.size() || end >= log.size() || log[end] != '/')
		return "";
	return log.substr(at + 16, end - at - 16);
}

// The whole JPEG parts of a multipart stream (Content-Length framed, as
// uStreamer sends them); a part cut short at the end is left out.
inline std::vector<std::string> mjpegParts(const std::string &stream)
{
	std::vector<std::string> parts;
	size_t at = 0;
	const std::string key = "Content-Length: ";
	while ((at = stream.find(key, at)) != std::string::npos) {
		size_t end = stream.find("\r\n", at);
		size_t body = stream.find("\r\n\r\n", at);
		if (end == std::string::npos || body == std::string::npos)
			break;
		size_t length = std::stoul(stream.substr(at + key.size(), end - at - key.size()));
		body += 4;
		if (body + length > stream.size())
			break;
		parts.push_back(stream.substr(body, length));
		at = body + length;
	}
	return parts;
}

// Headless Chromium (Debian's chromium) as the page tests run it, at the
// window size given ("1280,1600"), to be followed by --dump-dom or
// --screenshot=FILE and the URL; it stops loading after 8 s (--timeout).
inline bool chromiumInstalled()
{
	int status = 0;
	run("command -v chromium", status);
	return status == 0;
}
inline std::string headlessChromium(const std::string &windowSize)
{
	return "timeout 60 chromium --headless=new --no-sandbox --disable-gpu --disable-background-networking "
	       "--disable-component-update --no-first-run --hide-scrollbars --window-size=" +
	       windowSize + " --timeout=8000 ";
}

// The newest frame number in the shared-memory output `name` (0 if it
// cannot be opened): the daemon's published frame count, read as a reader would.
inline uint64_t latestSharedFrame(const std::string &name)
{
	dk_shm_reader r;
	uint64_t frame = 0;
	if (dk_shm_open(name.c_str(), &r) == 0) {
		dk_shm_latest(&r, &frame);
		dk_shm_close(&r);
	}
	return frame;
}

} // namespace depthkey::test
