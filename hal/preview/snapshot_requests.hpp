// A snapshot asked for from the preview page (POST /snapshot, issue 30):
// the same stage pictures SIGUSR1 writes into daemon.snapshot_dir. The
// HTTP thread that got the request waits here; the daemon's loop sees it
// pending (an atomic load per frame tick), writes the pictures between
// frames, and answers with what it wrote or why it could not. One request
// at a time, and at most one per kMinIntervalNs: each writes a dozen PNGs
// (about 0.3 s of the loop's time at 640x480), which a client pressing the
// button, or a script, must not turn into a stall.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <string>

namespace depthkey {

struct SnapshotReply {
	unsigned httpStatus = 0; // 200, 409 (no snapshot_dir), 429 (too soon), 500, 503 (no answer)
	std::string message;     // what was written, or why not
};

class SnapshotRequests
{
public:
	static constexpr uint64_t kMinIntervalNs = 2'000'000'000u;

	// HTTP thread: asks for a snapshot at nowNs (CLOCK_MONOTONIC) and
	// waits up to timeout for the loop's answer.
	SnapshotReply request(uint64_t nowNs, std::chrono::milliseconds timeout);
	// The loop: whether a request waits for a snapshot.
	bool pending() const { return pending_.load(std::memory_order_relaxed); }
	// The loop, after writing (ret 0) or failing (a negative errno;
	// -ENOENT: no snapshot_dir set); nothing when no request waits.
	void answer(int ret, const std::string &message);
	// Wakes a waiting request with 503 (the server stops).
	void cancel();

private:
	std::mutex mutex_;
	std::condition_variable answered_;
	std::atomic<bool> pending_{ false };
	bool busy_ = false;        // a request waits (others get 429)
	bool haveAnswer_ = false;
	SnapshotReply reply_;
	uint64_t lastNs_ = 0;
	bool any_ = false;         // a request was taken since the start
};

} // namespace depthkey
