// The SR-2's USB function served from userspace through FunctionFS: answers
// the vendor frame request (0xB0) on ep0, sends frames rendered from the
// simulated scene on bulk IN 0x88 and takes register writes on bulk OUT 0x02.
// Faults are injected between requests: a stalled camera (requests acked,
// no data), short/corrupt/flat transfers, protocol STALLs of the request.
//
// Threads: the caller's thread polls ep0 (handleEp0 when readable); one
// thread writes frames, one reads registers, because FunctionFS endpoint
// files only block (no poll).
#pragma once

#include "hal/sim/simple_scene.hpp"
#include "hal/unique_fd.hpp"
#include "tools/sr2_emulator/sr2_frame_encoder.hpp"

#include <atomic>
#include <condition_variable>
#include <linux/usb/ch9.h>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>

namespace depthkey {

struct Sr2FunctionCounters {
	uint64_t requests = 0;  // 0xB0 requests acked
	uint64_t ignored = 0;   // acked while stalled
	uint64_t halted = 0;    // answered with a protocol STALL
	uint64_t sent = 0;      // frames written completely
	uint64_t faulty = 0;    // of those, with an injected fault
	uint64_t dropped = 0;   // frames the host never took (unplug, reset)
	uint64_t registers = 0; // register writes received
};

class Sr2Function
{
public:
	explicit Sr2Function(uint64_t seed, int maxFps) : scene_(seed), maxFps_(maxFps) {}
	~Sr2Function() { close(); }

	// Writes descriptors and strings to ffsDir/ep0, opens the endpoint files
	// and starts the endpoint threads. Then the gadget may be bound.
	int open(const std::string &ffsDir);
	int ep0Fd() const { return ep0_.get(); }
	// Reads and answers the pending ep0 events.
	void handleEp0();
	void close();

	// Fault injection; each applies from the next frame request on.
	void setStalled(bool stalled);
	void injectFrameFaults(Sr2FrameFault fault, int count);
	void injectHalts(int count);

	Sr2FunctionCounters counters();

private:
	void onSetup(const usb_ctrlrequest &setup);
	void frameLoop();
	void registerLoop();
	Sr2FrameFault takeFault();

	SimpleScene scene_;
	int maxFps_;
	UniqueFd ep0_, epIn_, epOut_;
	std::thread frameThread_, registerThread_;
	std::atomic<bool> stopping_{ false };
	std::atomic<bool> stalled_{ false };
	std::atomic<bool> frameDone_{ false }, registerDone_{ false };

	std::mutex mutex_;              // guards what follows
	std::condition_variable requested_;
	int pendingRequests_ = 0;
	Sr2FrameFault fault_ = Sr2FrameFault::None;
	int faultCount_ = 0;
	int haltCount_ = 0;
	Sr2FunctionCounters counters_;
};

} // namespace depthkey
