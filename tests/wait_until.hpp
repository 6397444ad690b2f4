// Waiting in a test for something to happen: poll until it holds or a
// deadline passes, instead of sleeping a fixed time that is longer than
// needed on an idle machine and too short on a loaded one. (A test that
// measures what happens during a window, e.g. no watchdog message for
// 1.5 s, still sleeps for that window.)
#pragma once

#include <chrono>
#include <thread>

namespace depthkey::test {

// Calls pred every step until it returns true, or until the deadline has
// passed (pred is called once more at the deadline). Returns pred's last
// answer, so a caller can assert on it or go on to the assertions that say
// what was missing.
template<typename Pred>
bool waitUntil(Pred &&pred, std::chrono::steady_clock::time_point deadline,
	       std::chrono::milliseconds step = std::chrono::milliseconds(10))
{
	for (;;) {
		const bool late = std::chrono::steady_clock::now() >= deadline;
		if (pred())
			return true;
		if (late)
			return false;
		std::this_thread::sleep_for(step);
	}
}

template<typename Pred>
bool waitUntil(Pred &&pred, std::chrono::milliseconds timeout,
	       std::chrono::milliseconds step = std::chrono::milliseconds(10))
{
	return waitUntil(pred, std::chrono::steady_clock::now() + timeout, step);
}

} // namespace depthkey::test
