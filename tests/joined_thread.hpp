// A test's helper thread that is stopped and joined however the test leaves
// its scope: an ASSERT_* that fails returns early, and a std::thread still
// joinable then ends the whole test binary (std::terminate), taking every
// later test's result with it (a unit run at load 18 lost the rest of the
// suite that way, 7 December).
#pragma once

#include <functional>
#include <thread>
#include <utility>

namespace depthkey::test {

class JoinedThread
{
public:
	// `stop` tells the thread's loop to end (it is called before the join).
	template <typename F>
	JoinedThread(std::function<void()> stop, F &&body) : stop_(std::move(stop)), thread_(std::forward<F>(body))
	{
	}
	~JoinedThread() { join(); }
	JoinedThread(const JoinedThread &) = delete;
	JoinedThread &operator=(const JoinedThread &) = delete;

	void join()
	{
		if (!thread_.joinable())
			return;
		if (stop_)
			stop_();
		thread_.join();
	}

private:
	std::function<void()> stop_;
	std::thread thread_;
};

} // namespace depthkey::test
