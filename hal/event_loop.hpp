// The daemon's single event loop: a thin owner of an sd-event loop that hands
// out RAII event sources. Devices register their fds and timers here so that a
// stalled device never blocks another one, the LEDs or the watchdog.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>

struct sd_event;
struct sd_event_source;

namespace depthkey {

// Owns one sd_event_source and the callback it calls. Destroying or resetting
// it removes the source from the loop, so an object that owns its sources can
// never be called back after it is gone.
class EventSource
{
public:
	EventSource() = default;
	~EventSource() { reset(); }
	EventSource(EventSource &&other) noexcept;
	EventSource &operator=(EventSource &&other) noexcept;
	EventSource(const EventSource &) = delete;
	EventSource &operator=(const EventSource &) = delete;

	void reset();
	bool active() const { return source_ != nullptr; }

	// Heap-held so that its address, the sd-event userdata, survives a move;
	// shared so that a callback may reset its own source while it runs.
	struct Handler : std::enable_shared_from_this<Handler> {
		Handler(std::function<void(uint32_t)> cb, uint64_t period)
			: callback(std::move(cb)), periodUs(period) {}
		std::function<void(uint32_t)> callback;
		uint64_t periodUs = 0; // non-zero for periodic timers
	};

private:
	friend class EventLoop;
	sd_event_source *source_ = nullptr;
	std::shared_ptr<Handler> handler_;
};

class EventLoop
{
public:
	EventLoop() = default;
	~EventLoop();
	EventLoop(const EventLoop &) = delete;
	EventLoop &operator=(const EventLoop &) = delete;

	int open(); // negative errno

	// One-shot timer, delayUs from now (CLOCK_MONOTONIC).
	int addTimer(uint64_t delayUs, std::function<void()> callback, EventSource &source);
	// Repeating timer; a late tick is not repeated to catch up.
	int addPeriodic(uint64_t periodUs, std::function<void()> callback, EventSource &source);
	// fd readiness; the callback receives the EPOLL* revents.
	int addIo(int fd, uint32_t events, std::function<void(uint32_t)> callback, EventSource &source);
	// The signal must be blocked (see blockSignals) before it is added.
	int addSignal(int signal, std::function<void()> callback, EventSource &source);
	// Runs after every event dispatch (used to drive libusb's own event handling).
	int addPost(std::function<void()> callback, EventSource &source);

	int run();                 // until exit(); returns the exit code
	void exit(int code);
	uint64_t nowUs() const;    // CLOCK_MONOTONIC
	sd_event *handle() { return event_; }

	static int blockSignals(std::initializer_list<int> signals);

private:
	sd_event *event_ = nullptr;
};

} // namespace depthkey
