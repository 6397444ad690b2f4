#include "tests/process/daemon_process.hpp"

#include "tests/test_paths.hpp"
#include "tests/wait_until.hpp"

#include <csignal>
#include <cstdlib>
#include <fcntl.h>
#include <fstream>
#include <poll.h>
#include <sstream>
#include <sys/socket.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

namespace depthkey::test {

DaemonProcess::DaemonProcess()
{
	char tmpl[] = "/tmp/depthkey-test-XXXXXX";
	if (mkdtemp(tmpl))
		dir_ = tmpl;
}

DaemonProcess::~DaemonProcess()
{
	if (pid_ > 0 && exitStatus_ < 0) {
		kill(pid_, SIGKILL);
		waitpid(pid_, nullptr, 0);
	}
	if (socket_ >= 0)
		close(socket_);
	if (!dir_.empty() && !std::getenv("DEPTHKEY_KEEP_TEST_DIRS"))
		std::system(("rm -rf '" + dir_ + "'").c_str());
}

// Test daemons serve their preview page on a port of the kernel's choosing,
// never the default 8080 that parallel test runs (and a real daemon) share.
// Added to the config the daemon runs on unless the test sets [preview].
void DaemonProcess::ephemeralPreview(const std::string &path) const
{
	std::ifstream in(path);
	std::stringstream text;
	text << in.rdbuf();
	if (text.str().find("[preview]") == std::string::npos)
		std::ofstream(path, std::ios::app) << "\n[preview]\nlisten = \"127.0.0.1:0\"\n";
}

std::string DaemonProcess::writeFile(const std::string &name, const std::string &text) const
{
	std::string path = dir_ + "/" + name;
	std::ofstream(path) << text;
	if (path == configPath_)
		ephemeralPreview(path);
	return path;
}

bool DaemonProcess::start(const std::vector<std::string> &args, unsigned long watchdogUsec)
{
	for (size_t i = 0; i + 1 < args.size(); i++)
		if (args[i] == "--config") {
			configPath_ = args[i + 1];
			ephemeralPreview(configPath_);
		}
	std::string socketPath = dir_ + "/notify.sock";
	socket_ = socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
	sockaddr_un addr{};
	addr.sun_family = AF_UNIX;
	if (socket_ < 0 || socketPath.size() >= sizeof(addr.sun_path))
		return false;
	socketPath.copy(addr.sun_path, sizeof(addr.sun_path) - 1);
	if (bind(socket_, reinterpret_cast<sockaddr *>(&addr), sizeof(addr)) < 0)
		return false;

	std::string binary = binDir() + "/depthkeyd";
	std::string logPath = dir_ + "/daemon.log";
	pid_ = fork();
	if (pid_ < 0)
		return false;
	if (pid_ == 0) {
		int log = open(logPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
		dup2(log, STDERR_FILENO);
		setenv("NOTIFY_SOCKET", socketPath.c_str(), 1);
		setenv("DEPTHKEY_LOG", "stderr", 1);
		unsetenv("WATCHDOG_PID");
		for (const auto &[name, value] : env_)
			setenv(name.c_str(), value.c_str(), 1);
		if (watchdogUsec)
			setenv("WATCHDOG_USEC", std::to_string(watchdogUsec).c_str(), 1);
		else
			unsetenv("WATCHDOG_USEC");
		std::vector<char *> argv;
		argv.push_back(const_cast<char *>(binary.c_str()));
		for (const std::string &a : args)
			argv.push_back(const_cast<char *>(a.c_str()));
		argv.push_back(nullptr);
		execv(binary.c_str(), argv.data());
		_exit(127);
	}
	return true;
}

bool DaemonProcess::receive(std::chrono::milliseconds timeout)
{
	pollfd pfd{ socket_, POLLIN, 0 };
	if (poll(&pfd, 1, static_cast<int>(timeout.count())) <= 0)
		return false;
	char buf[4096];
	ssize_t n = recv(socket_, buf, sizeof(buf), MSG_DONTWAIT);
	if (n <= 0)
		return false;
	messages_.emplace_back(buf, static_cast<size_t>(n));
	return true;
}

void DaemonProcess::pollNotify()
{
	while (receive(std::chrono::milliseconds(0))) {
	}
}

bool DaemonProcess::waitForNotify(const std::string &text, std::chrono::milliseconds timeout)
{
	auto deadline = std::chrono::steady_clock::now() + timeout;
	size_t seen = messages_.size();
	for (;;) {
		for (; seen < messages_.size(); ++seen)
			if (messages_[seen].find(text) != std::string::npos)
				return true;
		auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
			deadline - std::chrono::steady_clock::now());
		if (left.count() <= 0)
			return false;
		receive(left);
	}
}

int DaemonProcess::countNotify(const std::string &text) const
{
	int n = 0;
	for (const std::string &m : messages_)
		n += m.find(text) != std::string::npos;
	return n;
}

bool DaemonProcess::running()
{
	if (pid_ <= 0 || exitStatus_ >= 0)
		return false;
	int status;
	if (waitpid(pid_, &status, WNOHANG) == pid_) {
		exitStatus_ = status;
		return false;
	}
	return true;
}

int DaemonProcess::signal(int sig)
{
	return kill(pid_, sig);
}

int DaemonProcess::waitExit(std::chrono::milliseconds timeout)
{
	if (!waitUntil([this] { return !running(); }, timeout))
		return -1;
	return exitStatus_;
}

std::string DaemonProcess::log() const
{
	std::ifstream in(dir_ + "/daemon.log");
	std::stringstream ss;
	ss << in.rdbuf();
	return ss.str();
}

} // namespace depthkey::test
