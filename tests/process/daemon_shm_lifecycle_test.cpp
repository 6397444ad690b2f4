// Issue 31, with the real depthkeyd: a second daemon on the same
// shared-memory names exits with status 1 and one line instead of running
// at 0 fps; a reload that renames the outputs removes the old objects; a
// clean stop removes what the daemon created.
#include "tests/process/daemon_process.hpp"
#include "tests/shm_test_util.hpp"
#include "tests/wait_until.hpp"

#include <gtest/gtest.h>

#include <csignal>
#include <fcntl.h>
#include <cstdio>
#include <sys/mman.h>
#include <sys/wait.h>

using namespace std::chrono_literals;
using depthkey::test::DaemonProcess;
using depthkey::test::openStatus;

namespace {

std::string outputConfig(const std::string &prefix)
{
	return "[colour]\nwidth = 160\nheight = 120\n[output]\ncomposite_name = \"" + prefix +
	       ".composite\"\nlecturer_name = \"" + prefix + ".lecturer\"\n";
}

// Whether a stream's readers' object (NAME.readers) is still in /dev/shm.
bool readersObjectLeft(const std::string &prefix)
{
	for (const char *stream : { ".composite", ".lecturer" }) {
		const int fd = shm_open((prefix + stream + DK_SHM_PRESENCE_SUFFIX).c_str(), O_RDONLY, 0);
		if (fd >= 0) {
			close(fd);
			return true;
		}
	}
	return false;
}

// The lines of the log that say something went wrong.
int countLines(const std::string &log, const std::string &text)
{
	int n = 0;
	for (size_t at = log.find(text); at != std::string::npos; at = log.find(text, at + 1))
		n++;
	return n;
}

} // namespace

// A second daemon that must not run: it exits at once, status 1, never
// ready, with exactly one line saying why (and no other line on it).
static void expectExitedWithOneLine(DaemonProcess &second, const std::string &line, const std::string &keyword)
{
	const int status = second.waitExit(10s);
	ASSERT_NE(status, -1) << "the second daemon runs on: " << second.log();
	ASSERT_TRUE(WIFEXITED(status)) << second.log();
	EXPECT_EQ(WEXITSTATUS(status), 1) << second.log();
	EXPECT_EQ(second.countNotify("READY=1"), 0);
	const std::string log = second.log();
	EXPECT_EQ(countLines(log, line), 1) << log;
	EXPECT_EQ(countLines(log, keyword), 1) << "one line, not two: " << log;
}

TEST(DaemonShmLifecycle, ASecondDaemonOnTheSameNamesExitsWithOneLine)
{
	const std::string prefix = "/depthkey-two-" + std::to_string(getpid());
	DaemonProcess first, second;
	ASSERT_TRUE(first.start({ "--config", first.writeFile("depthkey.toml", outputConfig(prefix)) }));
	ASSERT_TRUE(first.waitForNotify("READY=1", 10s)) << first.log();

	ASSERT_TRUE(second.start({ "--config", second.writeFile("depthkey.toml", outputConfig(prefix)) }));
	expectExitedWithOneLine(second, "cannot start: " + prefix + ".composite: lock: another writer has it open",
				"another writer");

	// The first keeps publishing under its names, untouched.
	EXPECT_TRUE(first.running());
	EXPECT_EQ(openStatus((prefix + ".composite").c_str()), 0);
	EXPECT_EQ(openStatus((prefix + ".lecturer").c_str()), 0);
	ASSERT_EQ(first.signal(SIGTERM), 0);
	EXPECT_NE(first.waitExit(5s), -1);
	depthkey::test::unlinkStreams(prefix);
}

// Issue 30: a second daemon with its own output names but the first one's
// preview port exits at once, status 1, one line naming the port.
TEST(DaemonShmLifecycle, ASecondDaemonOnTheSamePreviewPortExitsWithOneLine)
{
	const std::string prefix = "/depthkey-port-" + std::to_string(getpid());
	DaemonProcess first, second;
	ASSERT_TRUE(first.start({ "--config", first.writeFile("depthkey.toml", outputConfig(prefix + "-a")) }));
	ASSERT_TRUE(first.waitForNotify("READY=1", 10s)) << first.log();
	int port = 0;
	ASSERT_TRUE(depthkey::test::waitUntil(
		[&] {
			size_t at = first.log().find("preview page at http://127.0.0.1:");
			return at != std::string::npos &&
			       std::sscanf(first.log().c_str() + at, "preview page at http://127.0.0.1:%d/", &port) == 1;
		},
		5s))
		<< first.log();

	const std::string listen = "127.0.0.1:" + std::to_string(port);
	ASSERT_TRUE(second.start({ "--config", second.writeFile("depthkey.toml", outputConfig(prefix + "-b") +
									 "[preview]\nlisten = \"" + listen + "\"\n") }));
	expectExitedWithOneLine(second, "cannot start: preview.listen " + listen + ": the port is in use", "in use");
	// It left nothing of its own names behind; the first runs on.
	EXPECT_EQ(openStatus((prefix + "-b.composite").c_str()), -ENOENT);
	EXPECT_TRUE(first.running());
	ASSERT_EQ(first.signal(SIGTERM), 0);
	EXPECT_NE(first.waitExit(5s), -1);
	depthkey::test::unlinkStreams(prefix + "-a");
	depthkey::test::unlinkStreams(prefix + "-b");
}

TEST(DaemonShmLifecycle, RenamesAndACleanStopLeaveNothingInDevShm)
{
	const std::string prefix = "/depthkey-mv-" + std::to_string(getpid());
	const std::string renamed = prefix + "-b";
	DaemonProcess daemon;
	const std::string config = daemon.writeFile("depthkey.toml", outputConfig(prefix));
	ASSERT_TRUE(daemon.start({ "--config", config }));
	ASSERT_TRUE(daemon.waitForNotify("READY=1", 10s)) << daemon.log();
	ASSERT_EQ(openStatus((prefix + ".composite").c_str()), 0);

	daemon.writeFile("depthkey.toml", outputConfig(renamed));
	ASSERT_EQ(daemon.signal(SIGHUP), 0);
	ASSERT_TRUE(depthkey::test::waitUntil(
		[&] {
			daemon.pollNotify();
			return daemon.countNotify("READY=1") >= 2;
		},
		10s))
		<< daemon.log();
	EXPECT_NE(daemon.log().find("configuration reloaded"), std::string::npos) << daemon.log();
	EXPECT_TRUE(depthkey::test::waitUntil([&] { return openStatus((renamed + ".composite").c_str()) == 0; }, 5s));
	// The old objects go once the new ones exist, the lecturer's after the
	// composite's: under SAN=1 on a loaded machine it was still there at the
	// first look (7 December).
	depthkey::test::waitUntil(
		[&] {
			return openStatus((prefix + ".composite").c_str()) == -ENOENT &&
			       openStatus((prefix + ".lecturer").c_str()) == -ENOENT;
		},
		5s);
	EXPECT_EQ(openStatus((prefix + ".composite").c_str()), -ENOENT);
	EXPECT_EQ(openStatus((prefix + ".lecturer").c_str()), -ENOENT);
	EXPECT_FALSE(readersObjectLeft(prefix));

	ASSERT_EQ(daemon.signal(SIGTERM), 0);
	const int status = daemon.waitExit(5s);
	ASSERT_NE(status, -1);
	EXPECT_EQ(WEXITSTATUS(status), 0);
	EXPECT_EQ(openStatus((renamed + ".composite").c_str()), -ENOENT);
	EXPECT_EQ(openStatus((renamed + ".lecturer").c_str()), -ENOENT);
	EXPECT_FALSE(readersObjectLeft(renamed));
	depthkey::test::unlinkStreams(prefix);
	depthkey::test::unlinkStreams(renamed);
}
