// Issue 14's reload cases against the real depthkeyd: a config that becomes
// a symlink to /dev/zero (C) or a FIFO (D), an unknown output.group (I), a
// config with thousands of errors (L), an [output] that cannot be opened,
// and a calibration for other frame sizes (N). Each time the daemon keeps
// publishing on its last good state and the log says why.
#include "config/calibration_file.hpp"
#include "hal/depthkey_shm.h"
#include "hal/shm_ring_writer.hpp"
#include "tests/process/daemon_process.hpp"
#include "tests/sample_calibration.hpp"
#include "tests/wait_until.hpp"
#include "tests/shm_test_util.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include <atomic>
#include <csignal>
#include <functional>
#include <sys/stat.h>
#include <sys/wait.h>
#include <thread>

using namespace std::chrono_literals;
using depthkey::test::DaemonProcess;

namespace {

std::string configText(const std::string &prefix, const std::string &extra = "")
{
	return "[colour]\nwidth = 160\nheight = 120\nfps = 25\n"
	       "[output]\ncomposite_name = \"" + prefix + ".composite\"\n"
	       "lecturer_name = \"" + prefix + ".lecturer\"\n" + extra;
}

// The newest frame number of an object, 0 when there is none (yet).
uint64_t latestFrame(const std::string &name)
{
	dk_shm_reader reader{};
	if (dk_shm_open(name.c_str(), &reader) != 0)
		return 0;
	uint64_t frame = 0;
	if (dk_shm_latest(&reader, &frame) != 0)
		frame = 0;
	dk_shm_close(&reader);
	return frame;
}

size_t count(const std::string &text, const std::string &what)
{
	size_t n = 0;
	for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1))
		n++;
	return n;
}

} // namespace

class DaemonReload : public testing::Test
{
protected:
	void SetUp() override
	{
		prefix_ = "/depthkey-rl-" + std::to_string(getpid());
		config_ = daemon_.writeFile("depthkey.toml", configText(prefix_));
	}
	void TearDown() override
	{
		daemon_.signal(SIGTERM);
		daemon_.waitExit(5s);
		depthkey::test::unlinkStreams(prefix_);
	}
	void startDaemon()
	{
		ASSERT_TRUE(daemon_.start({ "--config", config_ }));
		ASSERT_TRUE(daemon_.waitForNotify("READY=1", 10s)) << daemon_.log();
	}
	// SIGHUP, then: did the daemon stay up and keep publishing frames?
	void reloadAndExpectFrames(const std::string &why)
	{
		uint64_t before = latestFrame(prefix_ + ".composite");
		ASSERT_EQ(daemon_.signal(SIGHUP), 0);
		ASSERT_TRUE(daemon_.waitForNotify("RELOADING=1", 5s)) << why;
		// READY=1 again once the reload is applied or refused (and logged):
		// the parse runs on a worker, which a sanitizer build on a busy
		// machine makes slow.
		ASSERT_TRUE(daemon_.waitForNotify("READY=1", 10s)) << why << "\n" << daemon_.log();
		// 25 fps: four frames take 160 ms; 5 s leaves room for a sanitizer
		// build on a busy machine, while a stalled loop never gets there.
		depthkey::test::waitUntil(
			[&] { return latestFrame(prefix_ + ".composite") > before + 3 || !daemon_.running(); }, 5s, 20ms);
		EXPECT_TRUE(daemon_.running()) << why;
		EXPECT_GT(latestFrame(prefix_ + ".composite"), before + 3) << why << "\n" << daemon_.log();
	}
	void replaceConfig(const std::function<int(const char *)> &make)
	{
		unlink(config_.c_str());
		ASSERT_EQ(make(config_.c_str()), 0);
	}

	DaemonProcess daemon_;
	std::string prefix_;
	std::string config_;
};

TEST_F(DaemonReload, ConfigBecomingADeviceOrAFifoIsRefused)
{
	startDaemon();
	replaceConfig([](const char *path) { return symlink("/dev/zero", path); });
	reloadAndExpectFrames("symlink to /dev/zero");
	EXPECT_NE(daemon_.log().find("not a regular file (a character device)"), std::string::npos)
		<< daemon_.log();

	replaceConfig([](const char *path) { return mkfifo(path, 0600); });
	reloadAndExpectFrames("FIFO");
	EXPECT_NE(daemon_.log().find("not a regular file (a FIFO)"), std::string::npos) << daemon_.log();
	EXPECT_NE(daemon_.log().find("keeping the previous configuration"), std::string::npos);
}

TEST_F(DaemonReload, UnknownGroupKeepsTheOutput)
{
	startDaemon();
	daemon_.writeFile("depthkey.toml", configText(prefix_, "group = \"nosuchgroup\"\n"));
	reloadAndExpectFrames("output.group = nosuchgroup");
	EXPECT_NE(daemon_.log().find("output.group: \"nosuchgroup\" is not a group"), std::string::npos)
		<< daemon_.log();
}

TEST_F(DaemonReload, ThousandsOfErrorsGiveTwentyOneLines)
{
	startDaemon();
	std::string junk = "[segmentation]\n";
	for (int i = 0; i < 20000; i++)
		junk += "k" + std::to_string(i) + " = 1\n";
	daemon_.writeFile("depthkey.toml", junk);
	reloadAndExpectFrames("20000 errors");
	std::string log = daemon_.log();
	EXPECT_EQ(count(log, "config reload refused"), 21u) << log.substr(0, 4000);
	EXPECT_NE(log.find("and 19980 more errors"), std::string::npos);
}

// An [output] that cannot be opened (here: another writer holds the new
// name) must not cost the recorder the stream it has.
TEST_F(DaemonReload, OutputThatCannotOpenKeepsThePrevious)
{
	startDaemon();
	depthkey::ShmRingWriter squatter;
	const std::string taken = prefix_ + ".taken";
	ASSERT_EQ(squatter.open(taken, 8, 8, DK_SHM_FORMAT_RGB24, 2, ""), 0);
	daemon_.writeFile("depthkey.toml",
			  "[colour]\nwidth = 160\nheight = 120\nfps = 25\n[output]\ncomposite_name = \"" + taken +
				  "\"\nlecturer_name = \"" + prefix_ + ".lecturer\"\n");
	reloadAndExpectFrames("composite_name held by another writer");
	EXPECT_NE(daemon_.log().find("keeping the previous [output]"), std::string::npos) << daemon_.log();
	EXPECT_EQ(squatter.frameCount(), 0u);
	squatter.unlink();
}

// Case N: a calibration fitted for other image sizes: "calibration loaded",
// then "not calibrated", and nothing said why.
TEST_F(DaemonReload, CalibrationForOtherSizesSaysWhy)
{
	std::string calibration = daemon_.dir() + "/calibration.toml";
	std::string error;
	ASSERT_EQ(depthkey::writeCalibration(calibration, depthkey::test::sampleCalibration(), error), 0)
		<< error;
	config_ = daemon_.writeFile("depthkey.toml",
				    configText(prefix_, "[mapping]\ncalibration_file = \"" + calibration + "\"\n"));
	startDaemon();
	ASSERT_TRUE(daemon_.waitForNotify("calibration for other frame sizes", 5s));
	std::this_thread::sleep_for(1500ms); // the journal line comes with the status
	std::string log = daemon_.log();
	EXPECT_NE(log.find("fitted for colour 640x480 and depth 160x124"), std::string::npos) << log;
	EXPECT_NE(log.find("the cameras deliver colour 160x120"), std::string::npos) << log;
	EXPECT_EQ(count(log, "but the cameras deliver"), 1u) << log; // once, not every second
}

// Case B through the command line: --check-config on a FIFO returns at once.
TEST_F(DaemonReload, CheckConfigOnAFifoReturnsAtOnce)
{
	std::string fifo = daemon_.dir() + "/fifo.toml";
	ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
	ASSERT_TRUE(daemon_.start({ "--check-config", fifo }));
	int status = daemon_.waitExit(5s);
	ASSERT_NE(status, -1) << "--check-config blocked on a FIFO";
	EXPECT_EQ(WEXITSTATUS(status), 1);
	EXPECT_NE(daemon_.log().find("not a regular file (a FIFO)"), std::string::npos) << daemon_.log();
}

// Case M: a 50 MB config on SIGHUP gave 1.2 s without frames. The cap
// makes it 1 MiB at most, whose parse still takes several frame periods
// (make bench: BM_ReloadParse1MiB_*), so the parse runs off the loop: the
// frames must keep coming while a worst-case 1 MiB config is parsed.
TEST_F(DaemonReload, ParsingALargeConfigDoesNotStallFrames)
{
	startDaemon();
	std::string junk = "[segmentation]\n";
	// Below the 1 MiB cap with room for the test's own [preview] section.
	for (int i = 0; junk.size() < (1u << 20) - 1024; i++)
		junk += "key" + std::to_string(i) + " = 1\n";
	daemon_.writeFile("depthkey.toml", junk);

	std::atomic<bool> stop{ false };
	std::atomic<int64_t> worstGapMs{ 0 };
	std::atomic<bool> restart{ false }; // forget the gap in progress: the next window begins
	std::thread watcher([&] {
		uint64_t last = latestFrame(prefix_ + ".composite");
		auto lastChange = std::chrono::steady_clock::now();
		while (!stop) {
			uint64_t now = latestFrame(prefix_ + ".composite");
			auto t = std::chrono::steady_clock::now();
			if (restart.exchange(false))
				lastChange = t;
			if (now != last) {
				last = now;
				lastChange = t;
			}
			int64_t gap = std::chrono::duration_cast<std::chrono::milliseconds>(t - lastChange).count();
			if (gap > worstGapMs)
				worstGapMs = gap;
			std::this_thread::sleep_for(2ms);
		}
	});
	// The same daemon's worst gap without a reload, over as long: on a slow
	// or busy host its own frame work already leaves gaps near 100 ms (this
	// VM, at a third of its usual speed, saw 111-132 ms with the parse off
	// the loop), and the parse must add little to that.
	std::this_thread::sleep_for(500ms); // past the first frames' start-up
	worstGapMs = 0;
	restart = true;
	std::this_thread::sleep_for(2100ms);
	const int64_t baselineGapMs = worstGapMs.exchange(0);
	restart = true;
	daemon_.pollNotify();
	const int readyBefore = daemon_.countNotify("READY=1");
	for (int i = 0; i < 3; i++) {
		ASSERT_EQ(daemon_.signal(SIGHUP), 0);
		std::this_thread::sleep_for(700ms);
	}
	// The gaps are watched until a reload has been refused (READY=1 again;
	// SIGHUPs during a parse are folded into one more).
	depthkey::test::waitUntil(
		[&] {
			daemon_.pollNotify();
			return daemon_.countNotify("READY=1") > readyBefore;
		},
		10s, 20ms);
	stop = true;
	watcher.join();
	EXPECT_TRUE(daemon_.running());
	EXPECT_NE(daemon_.log().find("more errors"), std::string::npos) << daemon_.log().substr(0, 2000);
	// 40 ms a frame; a parse on the loop would leave a gap of 100-300 ms
	// (BM_ReloadParse1MiB_*: up to ~270 ms without sanitizers). Under ASan
	// the daemon's own frame work is 2-3 times slower and the parsing worker
	// takes the second of two cores: a 165 ms gap was seen with the parse
	// off the loop, while the same parse on the loop costs 500 ms or more.
	// The limit is the larger of a fixed one and the baseline plus a margin
	// well under a parse's cost. ThreadSanitizer slows the frames far more
	// (2.5 fps: a 491 ms gap without a reload, 708 ms with the parse off the
	// loop, on 5 December), and the parse with them: `depthkeyd
	// --check-config` on this config took 1.70 s in that build (0.15 s
	// plain), so a parse on the loop would add well over its margin.
#if defined(__SANITIZE_THREAD__)
	constexpr int64_t kMaxGapMs = 250, kMarginMs = 600;
#elif defined(__SANITIZE_ADDRESS__)
	constexpr int64_t kMaxGapMs = 250, kMarginMs = 120;
#else
	constexpr int64_t kMaxGapMs = 100, kMarginMs = 60;
#endif
	const int64_t limitMs = std::max(kMaxGapMs, baselineGapMs + kMarginMs);
	std::printf("    worst frame gap %lld ms during the reloads, %lld ms without (limit %lld ms)\n",
		    (long long)worstGapMs.load(), (long long)baselineGapMs, (long long)limitMs);
	EXPECT_LT(worstGapMs.load(), limitMs) << "frames stalled during a reload";
}

// output.v4l2_device on reload: a node that is no v4l2loopback output
// (/dev/null) is reported lost once (not once per retry or frame), the status
// line says so, the shared memory is not re-created under its readers, and
// "" turns the webcam off again.
TEST_F(DaemonReload, V4l2OutputIsAppliedWithoutReopeningTheSharedMemory)
{
	startDaemon();
	dk_shm_reader reader{};
	ASSERT_EQ(dk_shm_open((prefix_ + ".composite").c_str(), &reader), 0);
	daemon_.writeFile("depthkey.toml", configText(prefix_, "v4l2_device = \"/dev/null\"\n"));
	reloadAndExpectFrames("output.v4l2_device = /dev/null");
	std::this_thread::sleep_for(1500ms); // several retries (0.1, 0.2, 0.4, 0.5 s)
	EXPECT_EQ(count(daemon_.log(), "v4l2-output lost: /dev/null: not a V4L2 device"), 1u) << daemon_.log();
	EXPECT_TRUE(daemon_.waitForNotify("webcam /dev/null lost", 3s)) << daemon_.log();
	uint64_t frame = 0;
	EXPECT_EQ(dk_shm_latest(&reader, &frame), 0) << "the composite was re-created under its reader";

	daemon_.writeFile("depthkey.toml", configText(prefix_));
	reloadAndExpectFrames("output.v4l2_device = \"\"");
	EXPECT_NE(daemon_.log().find("v4l2-output off"), std::string::npos) << daemon_.log();
	EXPECT_EQ(dk_shm_latest(&reader, &frame), 0);
	dk_shm_close(&reader);
}

// Issue 31: a config that says it ends with [end] and was cut short (here
// before a new [output], whose names would then revert) is refused on
// reload, at its last line, and the running configuration is kept.
TEST_F(DaemonReload, AConfigCutShortIsRefusedAndThePreviousKept)
{
	const std::string marked = "[daemon]\nend_marker = true\n";
	daemon_.writeFile("depthkey.toml", marked + configText(prefix_) + "[end]\n");
	startDaemon();
	daemon_.writeFile("depthkey.toml", marked + "[colour]\nwidth = 160\nheight = 120\nfps = 25\n");
	reloadAndExpectFrames("cut before [output]");
	const std::string log = daemon_.log();
	EXPECT_NE(log.find("config reload refused: " + daemon_.dir() + "/depthkey.toml:"), std::string::npos) << log;
	EXPECT_NE(log.find(":1: end: missing section [end]: the file is cut short"), std::string::npos) << log;
	EXPECT_NE(log.find("keeping the previous configuration"), std::string::npos) << log;
	// (reloadAndExpectFrames saw the composite under the kept name go on.)
}
