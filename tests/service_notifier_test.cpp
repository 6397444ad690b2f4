// systemd's notify protocol as the daemon speaks it (daemon/service_notifier.hpp):
// the messages on a NOTIFY_SOCKET of our own, STATUS= only when it changes,
// no-ops without a socket, and WATCHDOG_USEC read as sd_watchdog_enabled does.
#include "daemon/service_notifier.hpp"
#include "hal/unique_fd.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>
#include <utility>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>
#include <vector>

using namespace depthkey;

namespace {

// A datagram socket standing in for systemd's, named in NOTIFY_SOCKET.
class NotifySocket
{
public:
	NotifySocket()
	{
		path_ = "/tmp/depthkey-notify-" + std::to_string(getpid()) + ".sock";
		fd_.reset(socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0));
		sockaddr_un addr{};
		addr.sun_family = AF_UNIX;
		path_.copy(addr.sun_path, sizeof(addr.sun_path) - 1);
		unlink(path_.c_str());
		ok_ = fd_.isValid() && bind(fd_.get(), reinterpret_cast<sockaddr *>(&addr), sizeof(addr)) == 0;
		setenv("NOTIFY_SOCKET", path_.c_str(), 1);
	}
	~NotifySocket() { unlink(path_.c_str()); }
	bool ok() const { return ok_; }
	// The datagrams that have arrived, without waiting.
	std::vector<std::string> received()
	{
		std::vector<std::string> messages;
		char buf[4096];
		for (ssize_t n; (n = recv(fd_.get(), buf, sizeof(buf), MSG_DONTWAIT)) > 0;)
			messages.emplace_back(buf, size_t(n));
		return messages;
	}

private:
	std::string path_;
	UniqueFd fd_;
	bool ok_ = false;
};

using Messages = std::vector<std::string>;

// The notify variables as the test process had them, back when it ends: a
// suite run under systemd keeps its own.
class NotifyEnvironment
{
public:
	NotifyEnvironment()
	{
		for (const char *name : kNames)
			if (const char *value = getenv(name))
				saved_.emplace_back(name, value);
	}
	~NotifyEnvironment()
	{
		for (const char *name : kNames)
			unsetenv(name);
		for (const auto &[name, value] : saved_)
			setenv(name.c_str(), value.c_str(), 1);
	}

private:
	static constexpr const char *kNames[] = { "NOTIFY_SOCKET", "WATCHDOG_USEC", "WATCHDOG_PID" };
	std::vector<std::pair<std::string, std::string>> saved_;
};

} // namespace

TEST(ServiceNotifier, SpeaksTheNotifyProtocol)
{
	NotifyEnvironment environment;
	NotifySocket systemd;
	ASSERT_TRUE(systemd.ok());
	ServiceNotifier notifier;
	notifier.ready();
	notifier.watchdog();
	notifier.reloading();
	notifier.reloaded(); // a reload ends with READY=1 again
	notifier.stopping();
	EXPECT_EQ(systemd.received(),
		  (Messages{ "READY=1", "WATCHDOG=1", "RELOADING=1", "READY=1", "STOPPING=1" }));
}

TEST(ServiceNotifier, StatusIsSentOnlyWhenItChanges)
{
	NotifyEnvironment environment;
	NotifySocket systemd;
	ASSERT_TRUE(systemd.ok());
	ServiceNotifier notifier;
	notifier.status("colour streaming");
	notifier.status("colour streaming"); // polled every second: no repeat
	notifier.status("colour lost");
	notifier.status("colour streaming");
	EXPECT_EQ(systemd.received(),
		  (Messages{ "STATUS=colour streaming", "STATUS=colour lost", "STATUS=colour streaming" }));
}

TEST(ServiceNotifier, WithoutASocketNothingIsSentAndNothingFails)
{
	NotifyEnvironment environment;
	unsetenv("NOTIFY_SOCKET");
	ServiceNotifier notifier;
	notifier.ready();
	notifier.status("running in a terminal");
	notifier.stopping();
	SUCCEED();
}

TEST(ServiceNotifier, WatchdogIntervalComesFromTheEnvironment)
{
	NotifyEnvironment environment;
	unsetenv("WATCHDOG_PID");
	unsetenv("WATCHDOG_USEC");
	EXPECT_EQ(ServiceNotifier::watchdogUsec(), 0u);
	setenv("WATCHDOG_USEC", "300000", 1);
	EXPECT_EQ(ServiceNotifier::watchdogUsec(), 300000u);
	// Meant for another process (systemd sets WATCHDOG_PID to the main PID).
	setenv("WATCHDOG_PID", std::to_string(getpid() + 1).c_str(), 1);
	EXPECT_EQ(ServiceNotifier::watchdogUsec(), 0u);
	setenv("WATCHDOG_PID", std::to_string(getpid()).c_str(), 1);
	EXPECT_EQ(ServiceNotifier::watchdogUsec(), 300000u);
}
