// Runs the real build/bin/depthkeyd as a child process with its own
// NOTIFY_SOCKET, so tests see exactly what systemd would see.
#pragma once

#include <chrono>
#include <string>
#include <utility>
#include <vector>

namespace depthkey::test {

class DaemonProcess
{
public:
	DaemonProcess();
	~DaemonProcess(); // kills a still running daemon

	// A fresh temporary folder for config, notify socket and logs. The
	// config given to start() (and rewritten here later) gets an ephemeral
	// preview port unless it has a [preview] section.
	const std::string &dir() const { return dir_; }
	std::string writeFile(const std::string &name, const std::string &text) const;

	// An extra environment variable for the daemon (set before start()).
	void setEnv(const std::string &name, const std::string &value) { env_.push_back({ name, value }); }

	// Starts depthkeyd with args; watchdogUsec > 0 sets WATCHDOG_USEC.
	bool start(const std::vector<std::string> &args, unsigned long watchdogUsec = 0);

	// Waits for a notify datagram containing `text` (e.g. "READY=1").
	bool waitForNotify(const std::string &text, std::chrono::milliseconds timeout);
	// Every datagram received so far.
	const std::vector<std::string> &notifications() const { return messages_; }
	int countNotify(const std::string &text) const;
	// Drains datagrams that have arrived, without waiting.
	void pollNotify();

	bool running();
	int signal(int sig);
	// Waits for exit; returns the wait status or -1 on timeout.
	int waitExit(std::chrono::milliseconds timeout);
	int pid() const { return pid_; }
	std::string log() const; // the daemon's stderr so far

private:
	bool receive(std::chrono::milliseconds timeout);
	void ephemeralPreview(const std::string &path) const;

	std::string dir_;
	std::string configPath_; // the --config the daemon runs on
	int socket_ = -1;
	int pid_ = -1;
	int exitStatus_ = -1;
	std::vector<std::string> messages_;
	std::vector<std::pair<std::string, std::string>> env_;
};

} // namespace depthkey::test
