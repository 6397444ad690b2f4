#include "hal/preview/snapshot_requests.hpp"

#include <cerrno>

namespace depthkey {

SnapshotReply SnapshotRequests::request(uint64_t nowNs, std::chrono::milliseconds timeout)
{
	std::unique_lock lock(mutex_);
	if (busy_ || (any_ && nowNs - lastNs_ < kMinIntervalNs))
		return { 429, "a snapshot was taken less than 2 s ago; try again in a moment" };
	busy_ = any_ = true;
	lastNs_ = nowNs;
	haveAnswer_ = false;
	pending_ = true;
	answered_.wait_for(lock, timeout, [this] { return haveAnswer_; });
	pending_ = false;
	busy_ = false;
	if (!haveAnswer_)
		return { 503, "the daemon did not write the snapshot within " + std::to_string(timeout.count() / 1000) +
				      " s (it may be stopping or reloading)" };
	return reply_;
}

void SnapshotRequests::answer(int ret, const std::string &message)
{
	std::lock_guard lock(mutex_);
	if (!pending_)
		return;
	pending_ = false;
	haveAnswer_ = true;
	reply_ = { ret == 0 ? 200u : ret == -ENOENT ? 409u : 500u, message };
	answered_.notify_all();
}

void SnapshotRequests::cancel()
{
	std::lock_guard lock(mutex_);
	if (!pending_)
		return;
	pending_ = false;
	haveAnswer_ = true;
	reply_ = { 503, "the preview is stopping: no snapshot" };
	answered_.notify_all();
}

} // namespace depthkey
