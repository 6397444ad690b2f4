// The TEST-ONLY fault switch (daemon/test_fault.hpp) in a running daemon: a
// stalled frame loop or a hung event loop must stop WATCHDOG=1, which is what
// makes systemd restart the daemon. The boot test (tests/boot/) checks the
// restart itself.
#include "tests/process/daemon_process.hpp"
#include "tests/shm_test_util.hpp"

#include <gtest/gtest.h>

#include <csignal>
#include <sys/mman.h>
#include <sys/wait.h>
#include <thread>

using namespace std::chrono_literals;
using depthkey::test::DaemonProcess;

namespace {

class TestFaultDaemon : public testing::Test
{
protected:
	void SetUp() override
	{
		prefix_ = "/depthkey-fault-" + std::to_string(getpid());
		config_ = daemon_.writeFile("depthkey.toml",
					    "[colour]\nwidth = 160\nheight = 120\n[output]\ncomposite_name = \"" +
						    prefix_ + ".composite\"\nlecturer_name = \"" + prefix_ +
						    ".lecturer\"\n");
	}
	void TearDown() override
	{
		depthkey::test::unlinkStreams(prefix_);
	}

	// Starts with the fault armed, waits for READY and a fed watchdog.
	void startArmed(const char *fault)
	{
		daemon_.setEnv("DEPTHKEY_TEST_FAULT", fault);
		ASSERT_TRUE(daemon_.start({ "--config", config_ }, 200000));
		ASSERT_TRUE(daemon_.waitForNotify("READY=1", 10s)) << daemon_.log();
		ASSERT_TRUE(daemon_.waitForNotify("WATCHDOG=1", 2s)) << daemon_.log();
	}

	// WATCHDOG=1 messages during `window`, after a grace period in which a
	// tick already under way may still arrive.
	int watchdogsDuring(std::chrono::milliseconds window)
	{
		std::this_thread::sleep_for(300ms);
		daemon_.pollNotify();
		int before = daemon_.countNotify("WATCHDOG=1");
		std::this_thread::sleep_for(window);
		daemon_.pollNotify();
		return daemon_.countNotify("WATCHDOG=1") - before;
	}

	DaemonProcess daemon_;
	std::string prefix_, config_;
};

} // namespace

TEST_F(TestFaultDaemon, StallStopsTheWatchdogButNotTheLoop)
{
	startArmed("stall");
	EXPECT_GE(watchdogsDuring(600ms), 2) << "watchdog not fed before the fault";
	ASSERT_EQ(daemon_.signal(SIGUSR2), 0);
	EXPECT_EQ(watchdogsDuring(1500ms), 0) << daemon_.log();
	// The loop itself runs on: the status says no frames go out any more.
	EXPECT_TRUE(daemon_.waitForNotify("output 0.0 fps", 3s)) << daemon_.log();
	EXPECT_TRUE(daemon_.running());
	EXPECT_NE(daemon_.log().find("TEST FAULT: frames stalled"), std::string::npos) << daemon_.log();
}

TEST_F(TestFaultDaemon, HangBlocksTheLoopUntilKilled)
{
	startArmed("hang");
	ASSERT_EQ(daemon_.signal(SIGUSR2), 0);
	EXPECT_EQ(watchdogsDuring(1500ms), 0) << daemon_.log();
	EXPECT_TRUE(daemon_.running());
	// SIGTERM is handled by the (now blocked) loop: nothing happens. systemd's
	// watchdog sends SIGABRT, which ends it.
	ASSERT_EQ(daemon_.signal(SIGTERM), 0);
	EXPECT_EQ(daemon_.waitExit(500ms), -1);
	ASSERT_EQ(daemon_.signal(SIGABRT), 0);
	int status = daemon_.waitExit(5s);
	ASSERT_NE(status, -1);
	EXPECT_TRUE(WIFSIGNALED(status));
}

TEST_F(TestFaultDaemon, UnknownValueIsIgnoredWithAWarning)
{
	startArmed("explode");
	EXPECT_NE(daemon_.log().find("DEPTHKEY_TEST_FAULT=explode ignored"), std::string::npos)
		<< daemon_.log();
	EXPECT_GE(watchdogsDuring(600ms), 2);
}
