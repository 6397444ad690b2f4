// The last few distinct error lines the daemon logged, with when they were
// last logged, for the preview page (issue 30): a technician at the page
// sees what went wrong without the journal. An error logged again moves to
// the front with its new time and a count; the oldest falls out.
#pragma once

#include <cstdint>
#include <deque>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

namespace depthkey {

struct RecentError {
	std::string message;
	uint64_t realtimeNs = 0; // CLOCK_REALTIME when last logged
	uint64_t count = 1;      // times logged while in the ring
};

class RecentErrors
{
public:
	static constexpr size_t kKept = 8;

	// Any thread (the keying worker logs too).
	void add(std::string_view message, uint64_t realtimeNs);
	// Newest first.
	std::vector<RecentError> list() const;

private:
	mutable std::mutex mutex_;
	std::deque<RecentError> errors_; // newest first, at most kKept
};

} // namespace depthkey
