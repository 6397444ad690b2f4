// One piece of slow, self-contained work (reading and parsing files) run on
// a worker thread, with its completion delivered back on the event loop's
// thread, so that the loop keeps publishing frames meanwhile.
//
// Why a reload needs it: the readers cap a config or calibration at 1 MiB,
// but parsing a hostile 1 MiB file still takes 75-270 ms on the target
// (tests/bench/config_parse_bench.cpp), several frame periods; a board
// image up to 4096x4096 takes as long to decode.
#pragma once

#include "hal/event_loop.hpp"
#include "hal/unique_fd.hpp"

#include <atomic>
#include <functional>
#include <thread>

namespace depthkey {

class BackgroundJob
{
public:
	BackgroundJob() = default;
	~BackgroundJob(); // waits for a running work() (bounded: it only reads files)
	BackgroundJob(const BackgroundJob &) = delete;
	BackgroundJob &operator=(const BackgroundJob &) = delete;

	// Runs work() on a new thread, then done() on the loop's thread. work()
	// must not touch what the loop thread uses; it hands its result to
	// done() through what both capture. -EBUSY while a job runs, or a
	// negative errno when no thread or eventfd can be had.
	int start(EventLoop &loop, std::function<void()> work, std::function<void()> done);
	bool running() const { return running_; }

private:
	void finish();

	UniqueFd eventFd_; // declared before source_: closed after it leaves the loop
	EventSource source_;
	std::thread thread_;
	std::function<void()> done_;
	bool running_ = false;
};

} // namespace depthkey
