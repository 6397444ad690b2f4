// How much of the event loop's time keying may take, so that a box too slow
// to key every colour frame keys fewer of them instead of starving
// everything else the one loop serves.
//
// Why: keying runs inside the loop. When it takes longer than a colour
// period (a slow board, a box also busy encoding, the HIL suite's VM at
// 170-190 ms a frame) the colour camera always has a frame ready and the
// loop never turns for the rest: the SR-2, which walks its protocol one USB
// transfer per turn, fell to 0-1 depth frames a second, so colour frames
// went out unpaired (no depth) for a minute; the board's capture stick was
// taken for lost, and a returning camera's re-open took over 2 s.
//
// A token bucket of loop time: every microsecond that passes earns
// the share (75 % by default) of a microsecond of keying, up to kBurstUs saved; keying a
// frame spends its time. A colour frame arriving with nothing to spend is
// shed (not keyed, counted). A box that keeps up (keying well under the
// period) never sheds: a 21 ms keying at 30 fps earns 25 ms a frame.
//
// Pure logic on times handed in (EventLoop::nowUs()), so tests drive it
// with a fake clock.
#pragma once

#include <algorithm>
#include <cstdint>

namespace depthkey {

class KeyingBudget
{
public:
	// Three quarters of the loop for keying by default (daemon.keying_share):
	// the rest (a few ms a frame on a real box) is depth, LEDs, readers,
	// the preview and the watchdog. A box whose devices need the loop more
	// often (the HIL suite's VM emulating them under TCG) sets less.
	static constexpr int kDefaultSharePercent = 75;
	// Keying saved for a short burst (a held loop resuming with a few
	// frames queued, a slow first frame), kept short so that a box keying
	// too slowly starts to shed within a few frames.
	static constexpr int64_t kBurstUs = 300'000;

	// The share of the loop's time keying may take, 10..100 percent.
	void setSharePercent(int percent) { shareQ8_ = std::clamp(percent, 10, 100) * 256 / 100; }

	// Whether a colour frame arriving at nowUs may be keyed; false counts
	// it as shed.
	bool admit(uint64_t nowUs)
	{
		earn(nowUs);
		if (creditUs_ > 0)
			return true;
		shed_++;
		return false;
	}
	// Keying a frame took us of the loop's time.
	void spend(uint64_t us) { creditUs_ -= int64_t(std::min<uint64_t>(us, kBurstUs * 4)); }
	uint64_t shed() const { return shed_; }

private:
	void earn(uint64_t nowUs)
	{
		if (started_ && nowUs > lastUs_)
			creditUs_ = std::min(kBurstUs, creditUs_ + int64_t(nowUs - lastUs_) * shareQ8_ / 256);
		started_ = true;
		lastUs_ = nowUs;
	}

	int64_t shareQ8_ = kDefaultSharePercent * 256 / 100;
	int64_t creditUs_ = kBurstUs;
	uint64_t lastUs_ = 0;
	uint64_t shed_ = 0;
	bool started_ = false;
};

} // namespace depthkey
