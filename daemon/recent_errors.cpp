#include "daemon/recent_errors.hpp"

#include <algorithm>

namespace depthkey {

void RecentErrors::add(std::string_view message, uint64_t realtimeNs)
{
	std::lock_guard lock(mutex_);
	RecentError entry{ std::string(message), realtimeNs, 1 };
	auto same = std::find_if(errors_.begin(), errors_.end(), [&](const RecentError &e) { return e.message == message; });
	if (same != errors_.end()) {
		entry.count = same->count + 1;
		errors_.erase(same);
	}
	errors_.push_front(std::move(entry));
	if (errors_.size() > kKept)
		errors_.pop_back();
}

std::vector<RecentError> RecentErrors::list() const
{
	std::lock_guard lock(mutex_);
	return { errors_.begin(), errors_.end() };
}

} // namespace depthkey
