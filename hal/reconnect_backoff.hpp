// When to try a lost device again, and when a streaming device counts as
// stalled. Pure logic on times handed in (CLOCK_MONOTONIC microseconds), so
// tests drive it with a fake clock; the backends feed it EventLoop::nowUs().
#pragma once

#include <algorithm>
#include <cstdint>

namespace depthkey {

// Retry delays 100 ms, 200 ms, capped at 250 ms. A returning device must be
// streaming again within 2 s: waiting for the next attempt (at most the cap)
// plus re-opening and the first frame (up to ~1.5 s for an SR-2 or the board's
// capture stick on a busy box, measured in the HIL VM) must fit in it; with a
// 1 s cap the VM measured 2.2-2.4 s under load, with 500 ms the board's stick
// 2.1-2.3 s. An attempt costs little (an open that fails: four a second
// while a camera is unplugged); the doubling keeps a device that opens and
// fails at once from spinning. The delay only
// starts again from the first one once the device delivered a good frame, so
// a device that opens and fails at once keeps backing off.
class ReconnectBackoff
{
public:
	static constexpr uint64_t kFirstUs = 100'000;
	static constexpr uint64_t kMaxUs = 250'000;

	// The delay before the next attempt; each call doubles the next one.
	uint64_t nextDelayUs()
	{
		uint64_t delay = nextUs_;
		nextUs_ = std::min(nextUs_ * 2, kMaxUs);
		attempts_++;
		return delay;
	}
	// A good frame arrived: the next loss retries quickly again.
	void reset()
	{
		nextUs_ = kFirstUs;
		attempts_ = 0;
	}
	uint64_t attempts() const { return attempts_; }

private:
	uint64_t nextUs_ = kFirstUs;
	uint64_t attempts_ = 0;
};

// No frame for timeoutUs while streaming means the device stalled.
class StallDetector
{
public:
	explicit StallDetector(uint64_t timeoutUs = 1'000'000) : timeoutUs_(timeoutUs) {}
	void setTimeout(uint64_t timeoutUs) { timeoutUs_ = timeoutUs; }
	// Streaming (re)started: the first frame gets a full timeout too.
	void arm(uint64_t nowUs) { lastUs_ = nowUs; }
	void frame(uint64_t nowUs) { lastUs_ = nowUs; }
	bool stalled(uint64_t nowUs) const { return nowUs > lastUs_ && nowUs - lastUs_ > timeoutUs_; }

private:
	uint64_t timeoutUs_;
	uint64_t lastUs_ = 0;
};

} // namespace depthkey
