// The real depthkeyd counts the recorders reading its output: depthkey-shmcat
// reading the composite shows up in STATUS ("readers 1") and the journal, and
// when it is killed it is counted gone within 2 s of its last heartbeat.
#include "tests/process/daemon_process.hpp"
#include "tests/test_paths.hpp"
#include "tests/shm_test_util.hpp"

#include <gtest/gtest.h>

#include <csignal>
#include <fcntl.h>
#include <sys/mman.h>
#include <sys/wait.h>

using namespace std::chrono_literals;
using depthkey::test::DaemonProcess;

TEST(DaemonReaderPresence, StatusCountsAReaderAndForgetsItWhenKilled)
{
	DaemonProcess daemon;
	const std::string prefix = "/depthkey-rp-" + std::to_string(getpid());
	const std::string config = daemon.writeFile(
		"depthkey.toml", "[colour]\nwidth = 160\nheight = 120\n[output]\ncomposite_name = \"" + prefix +
					 ".composite\"\nlecturer_name = \"" + prefix + ".lecturer\"\n");
	ASSERT_TRUE(daemon.start({ "--config", config }));
	ASSERT_TRUE(daemon.waitForNotify("READY=1", 10s)) << daemon.log();
	ASSERT_TRUE(daemon.waitForNotify("readers 0;", 3s)) << "no reader yet";

	const std::string shmcat = depthkey::test::binDir() + "/depthkey-shmcat";
	pid_t reader = fork();
	ASSERT_GE(reader, 0);
	if (reader == 0) {
		int null = open("/dev/null", O_WRONLY);
		dup2(null, STDOUT_FILENO);
		execl(shmcat.c_str(), shmcat.c_str(), "--name", (prefix + ".composite").c_str(), nullptr);
		_exit(127);
	}
	EXPECT_TRUE(daemon.waitForNotify("readers 1;", 4s)) << daemon.log();
	kill(reader, SIGKILL);
	int status;
	waitpid(reader, &status, 0);
	// Gone within DK_SHM_READER_TIMEOUT_MS + 250 ms, seen at the next 1 s
	// status tick.
	auto killedAt = std::chrono::steady_clock::now();
	EXPECT_TRUE(daemon.waitForNotify("readers 0;", 3500ms)) << daemon.log();
	EXPECT_LT(std::chrono::steady_clock::now() - killedAt, 3500ms);
	EXPECT_NE(daemon.log().find("readers: composite 1, lecturer 0, board-geometry lecturer 0"), std::string::npos) << daemon.log();
	EXPECT_NE(daemon.log().find("readers: composite 0, lecturer 0, board-geometry lecturer 0"), std::string::npos) << daemon.log();

	ASSERT_EQ(daemon.signal(SIGTERM), 0);
	EXPECT_NE(daemon.waitExit(5s), -1);
	depthkey::test::unlinkStreams(prefix);
}
