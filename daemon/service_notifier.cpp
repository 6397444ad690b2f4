#include "daemon/service_notifier.hpp"

#include <systemd/sd-daemon.h>

namespace depthkey {

void ServiceNotifier::ready()
{
	sd_notify(0, "READY=1");
}

void ServiceNotifier::reloading()
{
	sd_notify(0, "RELOADING=1");
}

void ServiceNotifier::reloaded()
{
	sd_notify(0, "READY=1");
}

void ServiceNotifier::stopping()
{
	sd_notify(0, "STOPPING=1");
}

void ServiceNotifier::watchdog()
{
	sd_notify(0, "WATCHDOG=1");
}

void ServiceNotifier::status(const std::string &text)
{
	if (text == lastStatus_)
		return;
	lastStatus_ = text;
	sd_notify(0, ("STATUS=" + text).c_str());
}

uint64_t ServiceNotifier::watchdogUsec()
{
	uint64_t usec = 0;
	if (sd_watchdog_enabled(0, &usec) <= 0)
		return 0;
	return usec;
}

} // namespace depthkey
