// A deadline for a connection's request head (issue 31, point 4). Clients
// that trickle a request a byte at a time are never idle long enough for
// libmicrohttpd's idle timeout, and 0.9.75 has no deadline of its own for a
// whole request; through `ssh -L` they share 127.0.0.1 with the technician,
// so a per-address cap alone leaves the technician behind them. A
// connection whose request head has not come whole within the deadline has
// its socket shut down (shutdown(2), not close: the descriptor stays
// libmicrohttpd's, which then closes it as for a client that left).
//
// libmicrohttpd tells opened() and closed() from its listening thread, and
// closed() before it closes the descriptor, so under the mutex a descriptor
// here is always still the connection's.
#pragma once

#include <atomic>
#include <cstdint>
#include <mutex>
#include <unordered_map>

namespace depthkey {

// The preview's deadline: a browser sends its request head in one packet;
// ssh -L over a slow link in a few.
inline constexpr uint64_t kRequestHeadDeadlineNs = 5'000'000'000ull;

class RequestDeadlines
{
public:
	explicit RequestDeadlines(uint64_t deadlineNs) : deadlineNs_(deadlineNs) {}

	void opened(const void *connection, int fd, uint64_t nowNs);
	void arrived(const void *connection); // its request head is whole
	void closed(const void *connection);
	// Shuts down the connections past their deadline at nowNs; returns how many.
	int expire(uint64_t nowNs);
	void clear();
	uint64_t expired() const { return expired_.load(); } // since the start
	size_t waiting() const;

private:
	struct Waiting {
		int fd;
		uint64_t sinceNs;
	};
	const uint64_t deadlineNs_;
	mutable std::mutex mutex_;
	std::unordered_map<const void *, Waiting> waiting_;
	std::atomic<uint64_t> expired_{ 0 };
};

} // namespace depthkey
