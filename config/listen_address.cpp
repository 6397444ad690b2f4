#include "config/listen_address.hpp"

#include <arpa/inet.h>
#include <charconv>
#include <cstring>
#include <netinet/in.h>

namespace depthkey {

std::string parseListenAddress(std::string_view text, ListenAddress &out)
{
	constexpr const char *kForm = "must be IP:PORT, e.g. \"127.0.0.1:8080\" or \"[::1]:8080\" (\"\" = off)";
	size_t colon = text.rfind(':');
	if (colon == std::string_view::npos || colon == 0 || colon + 1 == text.size())
		return kForm;
	std::string_view host = text.substr(0, colon), portText = text.substr(colon + 1);
	ListenAddress a;
	if (host.front() == '[') {
		if (host.size() < 3 || host.back() != ']')
			return kForm;
		a.ip = std::string(host.substr(1, host.size() - 2));
		a.ipv6 = true;
	} else {
		a.ip = std::string(host);
	}
	auto [end, ec] = std::from_chars(portText.data(), portText.data() + portText.size(), a.port);
	if (ec != std::errc() || end != portText.data() + portText.size() || a.port < 0 || a.port > 65535)
		return "port must be 0..65535";
	if (a.ipv6) {
		in6_addr v6{};
		if (inet_pton(AF_INET6, a.ip.c_str(), &v6) != 1)
			return "'" + a.ip + "' is not an IPv6 address";
		a.loopback = IN6_IS_ADDR_LOOPBACK(&v6);
	} else {
		in_addr v4{};
		if (inet_pton(AF_INET, a.ip.c_str(), &v4) != 1)
			return "'" + a.ip + "' is not an IPv4 address (host names are not accepted)";
		a.loopback = (ntohl(v4.s_addr) >> 24) == 127;
	}
	out = a;
	return "";
}

} // namespace depthkey
