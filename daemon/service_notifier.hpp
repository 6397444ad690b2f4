// systemd's notify protocol (sd_notify): READY=1, STATUS=, WATCHDOG=1,
// RELOADING=1, STOPPING=1. Without NOTIFY_SOCKET every call is a no-op, so the
// daemon behaves the same in a terminal.
#pragma once

#include <cstdint>
#include <string>

namespace depthkey {

class ServiceNotifier
{
public:
	void ready();
	void reloading();
	void reloaded();
	void stopping();
	void watchdog();
	// Sent only when it changes: the status line is polled every second.
	void status(const std::string &text);

	// The watchdog interval systemd asked for (WATCHDOG_USEC), 0 if none.
	static uint64_t watchdogUsec();

private:
	std::string lastStatus_;
};

} // namespace depthkey
