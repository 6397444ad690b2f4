// The preview's listening socket, which is ours rather than libmicrohttpd's:
// it is bound when the daemon starts (a port in use is an error then), and
// the library is loaded only when a client knocks on it
// (hal/preview/microhttpd_library.hpp).
#pragma once

#include "config/listen_address.hpp"
#include "hal/unique_fd.hpp"

#include <string>

namespace depthkey {

// Connections the kernel queues before libmicrohttpd accepts them.
inline constexpr int kListenBacklog = 16;

// Binds and listens on address. Returns 0, or a negative errno with error
// naming the address and the step that failed.
int listenOn(const ListenAddress &address, UniqueFd &fd, std::string &error);
// The port fd is bound to (0 if unknown).
int boundPort(int fd);
// Answers the connection waiting on listenFd with 503 and why, then closes
// it: the server could not be started for it, and a client must not hang
// on a connection nobody will read.
void refuseWaitingClient(int listenFd, const std::string &why);

} // namespace depthkey
