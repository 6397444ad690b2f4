#include "tools/sr2_emulator/sr2_function.hpp"

#include "hal/sr2/sr2_protocol.hpp"
#include "tools/sr2_emulator/ffs_descriptors.hpp"

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fcntl.h>
#include <linux/usb/functionfs.h>
#include <unistd.h>
#include <vector>

namespace depthkey {

namespace {

int writeAll(int fd, const std::vector<uint8_t> &bytes)
{
	ssize_t n = ::write(fd, bytes.data(), bytes.size());
	if (n < 0)
		return -errno;
	return n == static_cast<ssize_t>(bytes.size()) ? 0 : -EIO;
}

double bootSeconds()
{
	timespec ts;
	clock_gettime(CLOCK_BOOTTIME, &ts);
	return static_cast<double>(ts.tv_sec) + static_cast<double>(ts.tv_nsec) * 1e-9;
}

double secondsSince(std::chrono::steady_clock::time_point start)
{
	return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Wakes the endpoint threads out of their blocking FunctionFS calls.
void noop(int) {}

} // namespace

int Sr2Function::open(const std::string &ffsDir)
{
	ep0_ = UniqueFd(::open((ffsDir + "/ep0").c_str(), O_RDWR | O_CLOEXEC));
	if (!ep0_.isValid())
		return -errno;
	int err = writeAll(ep0_.get(), sr2FunctionFsDescriptors(sr2::kEndpointFramesIn, sr2::kEndpointRegistersOut));
	if (!err)
		err = writeAll(ep0_.get(), sr2FunctionFsStrings());
	if (err) {
		std::fprintf(stderr, "sr2-emulator: FunctionFS refused the descriptors: %s\n", strerror(-err));
		return err;
	}
	// Endpoint files in the order of the descriptors: IN, then OUT.
	epIn_ = UniqueFd(::open((ffsDir + "/ep1").c_str(), O_RDWR | O_CLOEXEC));
	epOut_ = UniqueFd(::open((ffsDir + "/ep2").c_str(), O_RDWR | O_CLOEXEC));
	if (!epIn_.isValid() || !epOut_.isValid())
		return -errno;

	struct sigaction action = {};
	action.sa_handler = noop; // no SA_RESTART: blocked I/O returns EINTR
	sigaction(SIGUSR2, &action, nullptr);
	frameThread_ = std::thread([this] { frameLoop(); });
	registerThread_ = std::thread([this] { registerLoop(); });
	return 0;
}

void Sr2Function::close()
{
	stopping_ = true;
	requested_.notify_all();
	const std::pair<std::thread *, std::atomic<bool> *> threads[] = {
		{ &frameThread_, &frameDone_ }, { &registerThread_, &registerDone_ } };
	for (auto [thread, done] : threads) {
		if (!thread->joinable())
			continue;
		// Repeated: a signal may land just before the thread blocks again.
		while (!*done) {
			pthread_kill(thread->native_handle(), SIGUSR2);
			std::this_thread::sleep_for(std::chrono::milliseconds(20));
		}
		thread->join();
	}
	// Only now, with no thread left in a read or write on them.
	for (UniqueFd *fd : { &epIn_, &epOut_, &ep0_ })
		fd->reset();
}

void Sr2Function::handleEp0()
{
	usb_functionfs_event events[4];
	ssize_t n = ::read(ep0_.get(), events, sizeof(events));
	if (n < 0)
		return;
	for (size_t i = 0; i < static_cast<size_t>(n) / sizeof(events[0]); i++) {
		switch (events[i].type) {
		case FUNCTIONFS_SETUP:
			onSetup(events[i].u.setup);
			break;
		case FUNCTIONFS_ENABLE:
			// When, as in /proc/uptime: the HIL tests time the daemon's
			// recovery from it (a timestamp added by whoever reads this
			// log may come seconds late in a busy VM).
			std::printf("sr2-emulator: host configured the device at %.3f\n", bootSeconds());
			break;
		case FUNCTIONFS_DISABLE:
		case FUNCTIONFS_UNBIND: {
			// The host is gone: its outstanding requests went with it.
			std::lock_guard lock(mutex_);
			pendingRequests_ = 0;
			break;
		}
		default:
			break;
		}
	}
}

void Sr2Function::onSetup(const usb_ctrlrequest &setup)
{
	bool frameRequest = setup.bRequestType == sr2::kRequestTypeVendorOut &&
			    setup.bRequest == sr2::kRequestFrame;
	bool halt = false;
	{
		std::lock_guard lock(mutex_);
		halt = !frameRequest || haltCount_ > 0;
		if (frameRequest && haltCount_ > 0) {
			haltCount_--;
			counters_.halted++;
		}
	}
	if (halt) {
		// A transfer in the wrong direction makes FunctionFS STALL ep0.
		if (setup.bRequestType & USB_DIR_IN)
			(void)!::read(ep0_.get(), nullptr, 0);
		else
			(void)!::write(ep0_.get(), nullptr, 0);
		return;
	}
	// No data stage: a zero-length read completes the status stage.
	(void)!::read(ep0_.get(), nullptr, 0);
	std::lock_guard lock(mutex_);
	counters_.requests++;
	if (stalled_) {
		counters_.ignored++;
		return;
	}
	// A real camera holds at most a frame or two; more requests than that
	// are the host retrying, not wanting more frames.
	pendingRequests_ = std::min(pendingRequests_ + 1, 2);
	requested_.notify_one();
}

Sr2FrameFault Sr2Function::takeFault()
{
	if (faultCount_ == 0)
		return Sr2FrameFault::None;
	faultCount_--;
	return fault_;
}

void Sr2Function::frameLoop()
{
	DepthFrame frame;
	frame.depthMm.resize(sr2::kWidth, sr2::kHeight);
	frame.amplitude.resize(sr2::kWidth, sr2::kHeight);
	frame.intensity.resize(sr2::kWidth, sr2::kHeight);
	std::vector<uint8_t> raw;
	const auto start = std::chrono::steady_clock::now();
	const auto period = std::chrono::microseconds(1000000 / std::max(1, maxFps_));
	auto nextFrame = start;
	uint64_t sequence = 0;
	while (!stopping_) {
		Sr2FrameFault fault;
		{
			std::unique_lock lock(mutex_);
			requested_.wait(lock, [this] { return stopping_ || pendingRequests_ > 0; });
			if (stopping_)
				break;
			pendingRequests_--;
			fault = takeFault();
		}
		// The sensor's integration time limits the frame rate.
		std::this_thread::sleep_until(nextFrame);
		nextFrame = std::max(nextFrame + period, std::chrono::steady_clock::now());
		scene_.renderDepth(secondsSince(start), frame);
		size_t length = encodeSr2Frame(frame, fault, ++sequence, raw);
		ssize_t n = ::write(epIn_.get(), raw.data(), length);
		std::lock_guard lock(mutex_);
		if (n == static_cast<ssize_t>(length)) {
			counters_.sent++;
			counters_.faulty += fault != Sr2FrameFault::None;
		} else {
			counters_.dropped++;
		}
	}
	frameDone_ = true;
}

void Sr2Function::registerLoop()
{
	uint8_t buffer[512];
	while (!stopping_) {
		ssize_t n = ::read(epOut_.get(), buffer, sizeof(buffer));
		if (n < 0) {
			if (errno != EINTR)
				std::this_thread::sleep_for(std::chrono::milliseconds(50));
			continue;
		}
		for (ssize_t i = 0; i + 1 < n; i += 2)
			std::printf("sr2-emulator: register 0x%02x = 0x%02x\n", buffer[i], buffer[i + 1]);
		std::lock_guard lock(mutex_);
		counters_.registers += static_cast<uint64_t>(n) / 2;
	}
	registerDone_ = true;
}

void Sr2Function::setStalled(bool stalled)
{
	stalled_ = stalled;
}

void Sr2Function::injectFrameFaults(Sr2FrameFault fault, int count)
{
	std::lock_guard lock(mutex_);
	fault_ = fault;
	faultCount_ = count;
}

void Sr2Function::injectHalts(int count)
{
	std::lock_guard lock(mutex_);
	haltCount_ = count;
}

Sr2FunctionCounters Sr2Function::counters()
{
	std::lock_guard lock(mutex_);
	return counters_;
}

} // namespace depthkey
