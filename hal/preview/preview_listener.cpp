#include "hal/preview/preview_listener.hpp"

#include <arpa/inet.h>
#include <cerrno>
#include <cstring>
#include <netinet/in.h>
#include <sys/socket.h>

namespace depthkey {

// The listening socket is ours, so that a bind failure has its own errno.
int listenOn(const ListenAddress &address, UniqueFd &fd, std::string &error)
{
	sockaddr_storage storage{};
	socklen_t length;
	if (address.ipv6) {
		auto *a = reinterpret_cast<sockaddr_in6 *>(&storage);
		a->sin6_family = AF_INET6;
		a->sin6_port = htons(static_cast<uint16_t>(address.port));
		inet_pton(AF_INET6, address.ip.c_str(), &a->sin6_addr);
		length = sizeof(*a);
	} else {
		auto *a = reinterpret_cast<sockaddr_in *>(&storage);
		a->sin_family = AF_INET;
		a->sin_port = htons(static_cast<uint16_t>(address.port));
		inet_pton(AF_INET, address.ip.c_str(), &a->sin_addr);
		length = sizeof(*a);
	}
	const std::string where = (address.ipv6 ? "[" + address.ip + "]" : address.ip) + ":" +
				  std::to_string(address.port);
	fd = UniqueFd(socket(storage.ss_family, SOCK_STREAM | SOCK_CLOEXEC, 0));
	int one = 1;
	const char *step = nullptr;
	if (!fd.isValid())
		step = "socket";
	else if (setsockopt(fd.get(), SOL_SOCKET, SO_REUSEADDR, &one, sizeof(one)) < 0)
		step = "SO_REUSEADDR";
	else if (address.ipv6 && setsockopt(fd.get(), IPPROTO_IPV6, IPV6_V6ONLY, &one, sizeof(one)) < 0)
		step = "IPV6_V6ONLY";
	else if (bind(fd.get(), reinterpret_cast<sockaddr *>(&storage), length) < 0)
		step = "bind";
	else if (listen(fd.get(), kListenBacklog) < 0)
		step = "listen";
	if (!step)
		return 0;
	int ret = -errno;
	error = "cannot listen on " + where + ": " + step + ": " + std::strerror(errno);
	fd.reset();
	return ret;
}

int boundPort(int fd)
{
	sockaddr_storage storage{};
	socklen_t length = sizeof(storage);
	if (getsockname(fd, reinterpret_cast<sockaddr *>(&storage), &length) < 0)
		return 0;
	if (storage.ss_family == AF_INET6)
		return ntohs(reinterpret_cast<sockaddr_in6 *>(&storage)->sin6_port);
	return ntohs(reinterpret_cast<sockaddr_in *>(&storage)->sin_port);
}

// Answers the connection waiting on listenFd with 503 and why, then closes
// it: the server could not be started for it, and a client must not hang
// on a connection nobody will read.
void refuseWaitingClient(int listenFd, const std::string &why)
{
	UniqueFd client(accept4(listenFd, nullptr, nullptr, SOCK_CLOEXEC | SOCK_NONBLOCK));
	if (!client.isValid())
		return;
	const std::string body = why + "\n";
	const std::string reply = "HTTP/1.1 503 Service Unavailable\r\nContent-Type: text/plain; charset=utf-8\r\n"
				  "Connection: close\r\nContent-Length: " +
				  std::to_string(body.size()) + "\r\n\r\n" + body;
	if (send(client.get(), reply.data(), reply.size(), MSG_NOSIGNAL | MSG_DONTWAIT) < 0) {
		// the client left already: nothing to tell it
	}
}


} // namespace depthkey
