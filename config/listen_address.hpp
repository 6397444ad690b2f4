// preview.listen: where the preview HTTP server listens, "IP:PORT" with an
// IPv4 literal ("127.0.0.1:8080") or a bracketed IPv6 one ("[::1]:8080").
// No host names: the box must not depend on a resolver to decide whether it
// is reachable from the school network. Port 0 asks the kernel for a free
// one (tests).
#pragma once

#include <string>
#include <string_view>

namespace depthkey {

struct ListenAddress {
	std::string ip;        // the literal, without brackets
	int port = 0;          // 0..65535
	bool ipv6 = false;
	bool loopback = false; // 127.0.0.0/8 or ::1: reachable from this box only
};

// Returns "" and fills out, or what is wrong with text.
std::string parseListenAddress(std::string_view text, ListenAddress &out);

} // namespace depthkey
