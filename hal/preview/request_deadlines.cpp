#include "hal/preview/request_deadlines.hpp"

#include <sys/socket.h>

namespace depthkey {

void RequestDeadlines::opened(const void *connection, int fd, uint64_t nowNs)
{
	std::lock_guard lock(mutex_);
	waiting_[connection] = { fd, nowNs };
}

void RequestDeadlines::arrived(const void *connection)
{
	std::lock_guard lock(mutex_);
	waiting_.erase(connection);
}

void RequestDeadlines::closed(const void *connection)
{
	std::lock_guard lock(mutex_);
	waiting_.erase(connection);
}

int RequestDeadlines::expire(uint64_t nowNs)
{
	std::lock_guard lock(mutex_);
	int count = 0;
	for (auto it = waiting_.begin(); it != waiting_.end();) {
		if (nowNs < it->second.sinceNs || nowNs - it->second.sinceNs < deadlineNs_) {
			++it;
			continue;
		}
		// Its thread's recv() returns 0: libmicrohttpd ends the connection.
		shutdown(it->second.fd, SHUT_RDWR);
		it = waiting_.erase(it);
		count++;
	}
	expired_ += static_cast<uint64_t>(count);
	return count;
}

void RequestDeadlines::clear()
{
	std::lock_guard lock(mutex_);
	waiting_.clear();
}

size_t RequestDeadlines::waiting() const
{
	std::lock_guard lock(mutex_);
	return waiting_.size();
}

} // namespace depthkey
