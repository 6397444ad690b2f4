// depthkey-sr2-emulator: a SwissRanger SR-2 made of a USB gadget
// (configfs + FunctionFS) that serves frames of the simulated scene, for
// hardware-in-the-loop tests of the real SR-2 backend over real usbfs. Needs
// root, configfs, libcomposite/usb_f_fs and a UDC (dummy_hcd in the test VM).
//
// Commands, one per line, on the control FIFO (acknowledged on stdout with
// "sr2-emulator: ok COMMAND"):
//   unplug | replug          unbind / bind the UDC
//   stall | resume           ack frame requests but send nothing / send again
//   short N | corrupt N | flat N   the next N frames broken that way
//   halt N                   answer the next N frame requests with a STALL
//   status                   print the counters
//   quit
#include "hal/sr2/sr2_protocol.hpp"
#include "tools/sr2_emulator/sr2_function.hpp"
#include "tools/sr2_emulator/usb_gadget.hpp"

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <poll.h>
#include <sstream>
#include <string>
#include <sys/signalfd.h>
#include <sys/stat.h>
#include <unistd.h>

using namespace depthkey;

namespace {

struct Options {
	std::string udc = "dummy_udc.0";
	std::string control;
	uint64_t seed = 1;
	int maxFps = 30;
};

void usage()
{
	std::fprintf(stderr,
		     "usage: depthkey-sr2-emulator [--udc NAME] [--control FIFO] [--seed N] [--max-fps N]\n"
		     "  an SR-2 (0852:0071) as a USB gadget on the UDC NAME (default dummy_udc.0);\n"
		     "  commands on FIFO: unplug replug stall resume short N corrupt N flat N halt N status quit\n");
}

bool parseOptions(int argc, char **argv, Options &options)
{
	for (int i = 1; i < argc; i++) {
		std::string arg = argv[i];
		if (i + 1 >= argc)
			return false;
		const char *value = argv[++i];
		if (arg == "--udc")
			options.udc = value;
		else if (arg == "--control")
			options.control = value;
		else if (arg == "--seed")
			options.seed = std::strtoull(value, nullptr, 10);
		else if (arg == "--max-fps")
			options.maxFps = std::atoi(value);
		else
			return false;
	}
	return options.maxFps > 0;
}

// Runs one command; false for quit.
bool runCommand(const std::string &line, UsbGadget &gadget, Sr2Function &function)
{
	std::istringstream words(line);
	std::string command;
	int count = 1;
	words >> command >> count;
	if (command.empty())
		return true;
	int err = 0;
	if (command == "quit")
		return false;
	else if (command == "unplug")
		err = gadget.unbind();
	else if (command == "replug")
		err = gadget.bind();
	else if (command == "stall" || command == "resume")
		function.setStalled(command == "stall");
	else if (command == "short")
		function.injectFrameFaults(Sr2FrameFault::Short, count);
	else if (command == "corrupt")
		function.injectFrameFaults(Sr2FrameFault::Corrupt, count);
	else if (command == "flat")
		function.injectFrameFaults(Sr2FrameFault::Flat, count);
	else if (command == "halt")
		function.injectHalts(count);
	else if (command == "status") {
		Sr2FunctionCounters c = function.counters();
		std::printf("sr2-emulator: status bound=%d requests=%llu ignored=%llu halted=%llu sent=%llu "
			    "faulty=%llu dropped=%llu registers=%llu\n",
			    gadget.bound(), (unsigned long long)c.requests, (unsigned long long)c.ignored,
			    (unsigned long long)c.halted, (unsigned long long)c.sent,
			    (unsigned long long)c.faulty, (unsigned long long)c.dropped,
			    (unsigned long long)c.registers);
	} else {
		std::printf("sr2-emulator: error unknown command '%s'\n", line.c_str());
		return true;
	}
	if (err)
		std::printf("sr2-emulator: error %s: %s\n", line.c_str(), strerror(-err));
	else
		std::printf("sr2-emulator: ok %s\n", line.c_str());
	return true;
}

int openControl(const std::string &path)
{
	if (path.empty())
		return -1;
	if (::mkfifo(path.c_str(), 0600) < 0 && errno != EEXIST) {
		std::fprintf(stderr, "sr2-emulator: cannot create %s: %s\n", path.c_str(), strerror(errno));
		return -1;
	}
	// Read-write, so the FIFO never reports end-of-file between writers.
	return ::open(path.c_str(), O_RDWR | O_NONBLOCK | O_CLOEXEC);
}

} // namespace

int main(int argc, char **argv)
{
	Options options;
	if (!parseOptions(argc, argv, options)) {
		usage();
		return 2;
	}
	std::setvbuf(stdout, nullptr, _IOLBF, 0);

	sigset_t signals;
	sigemptyset(&signals);
	sigaddset(&signals, SIGINT);
	sigaddset(&signals, SIGTERM);
	sigprocmask(SIG_BLOCK, &signals, nullptr);
	int signalFd = signalfd(-1, &signals, SFD_CLOEXEC);

	UsbGadget gadget("depthkey-sr2", options.udc);
	UsbGadgetIdentity identity{ sr2::kVendorId, sr2::kProductId, "CSEM (emulated by depthkey)",
				    "SwissRanger SR-2 (emulated)", "EMU0001" };
	if (gadget.open(identity) < 0)
		return 1;
	Sr2Function function(options.seed, options.maxFps);
	int err = function.open(gadget.functionFsDir());
	if (!err)
		err = gadget.bind();
	if (err) {
		std::fprintf(stderr, "sr2-emulator: cannot start on %s: %s\n", options.udc.c_str(), strerror(-err));
		function.close();
		return 1;
	}
	int control = openControl(options.control);
	std::printf("sr2-emulator: plugged into %s as %04x:%04x%s%s\n", options.udc.c_str(), sr2::kVendorId,
		    sr2::kProductId, control >= 0 ? ", commands on " : "", options.control.c_str());

	std::string pending;
	bool running = true;
	while (running) {
		pollfd fds[3] = { { function.ep0Fd(), POLLIN, 0 }, { signalFd, POLLIN, 0 }, { control, POLLIN, 0 } };
		if (poll(fds, control >= 0 ? 3 : 2, -1) < 0 && errno != EINTR)
			break;
		if (fds[0].revents & POLLIN)
			function.handleEp0();
		if (fds[1].revents & POLLIN)
			running = false;
		if (control >= 0 && (fds[2].revents & POLLIN)) {
			char buffer[256];
			ssize_t n;
			while ((n = ::read(control, buffer, sizeof(buffer))) > 0)
				pending.append(buffer, static_cast<size_t>(n));
			size_t end;
			while (running && (end = pending.find('\n')) != std::string::npos) {
				running = runCommand(pending.substr(0, end), gadget, function);
				pending.erase(0, end + 1);
			}
		}
	}
	gadget.unbind();
	function.close();
	gadget.close();
	std::printf("sr2-emulator: unplugged and removed\n");
	return 0;
}
