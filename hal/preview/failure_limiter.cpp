#include "hal/preview/failure_limiter.hpp"

namespace depthkey {

namespace {

// A window set to begin after a back-off is not over during it.
bool windowOver(uint64_t windowStartNs, uint64_t windowNs, uint64_t nowNs)
{
	return nowNs >= windowStartNs && nowNs - windowStartNs >= windowNs;
}

} // namespace

bool FailureLimiter::blocked(const std::string &address, uint64_t nowNs)
{
	std::lock_guard lock(mutex_);
	auto it = attempts_.find(address);
	return it != attempts_.end() && nowNs < it->second.blockedUntilNs;
}

bool FailureLimiter::failed(const std::string &address, uint64_t nowNs)
{
	std::lock_guard lock(mutex_);
	auto it = attempts_.find(address);
	if (it == attempts_.end()) {
		makeRoom(nowNs);
		it = attempts_.emplace(address, Attempts{ 0, nowNs, 0 }).first;
	}
	Attempts &a = it->second;
	if (windowOver(a.windowStartNs, limits_.windowNs, nowNs)) { // a new window
		a.failures = 0;
		a.windowStartNs = nowNs;
	}
	if (++a.failures < limits_.maxFailures)
		return false;
	a.failures = 0;
	a.windowStartNs = nowNs + limits_.backOffNs; // counting starts again after it
	a.blockedUntilNs = nowNs + limits_.backOffNs;
	return true;
}

void FailureLimiter::succeeded(const std::string &address)
{
	std::lock_guard lock(mutex_);
	attempts_.erase(address);
}

size_t FailureLimiter::addresses() const
{
	std::lock_guard lock(mutex_);
	return attempts_.size();
}

// Forgets the addresses whose window and back-off are over; if the table is
// still full, the one whose window began first. Runs only when a new
// address fails, so its linear scans cost nothing to a client that is known.
void FailureLimiter::makeRoom(uint64_t nowNs)
{
	if (attempts_.size() < limits_.maxAddresses)
		return;
	for (auto it = attempts_.begin(); it != attempts_.end();) {
		const Attempts &a = it->second;
		const bool over = nowNs >= a.blockedUntilNs && windowOver(a.windowStartNs, limits_.windowNs, nowNs);
		it = over ? attempts_.erase(it) : std::next(it);
	}
	if (attempts_.size() < limits_.maxAddresses)
		return;
	auto oldest = attempts_.begin();
	for (auto it = attempts_.begin(); it != attempts_.end(); ++it)
		if (it->second.windowStartNs < oldest->second.windowStartNs)
			oldest = it;
	attempts_.erase(oldest);
}

} // namespace depthkey
