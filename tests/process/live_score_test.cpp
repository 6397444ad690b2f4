// Issue 29: what the student sees, scored live. The daemon on the simulated
// cameras says its live score in STATUS= (and /status.json, /metrics: the
// unit tests of preview_status); on a Pi-class share of one core
// (cpu_share.sh) its live IoU over 60 s is depthkey-eval's for the same
// frames, and no frame shows the board alone while both cameras stream.
// The 60 s run is its own make target, `make live-share`, which sets
// DEPTHKEY_LIVE_SHARE=1; otherwise reported skipped.
#include "tests/process/daemon_process.hpp"
#include "tests/process/shell_command.hpp"
#include "tests/test_paths.hpp"
#include "tests/wait_until.hpp"

#include <cstdio>
#include <cstdlib>
#include <gtest/gtest.h>
#include <string>

using namespace std::chrono_literals;
using depthkey::test::DaemonProcess;
using depthkey::test::lastLine;
using depthkey::test::run;

namespace {

// "live IoU 0.962 BF 0.850 (5 s), 0.958 0.847 over 120 frames, 0 board-only"
struct LiveFigures {
	double recentIou = -1, recentBf = -1, iou = -1, bf = -1;
	long frames = -1, boardOnly = -1;
};

bool parseLive(const std::string &status, LiveFigures &f)
{
	const size_t at = status.find("live IoU ");
	return at != std::string::npos &&
	       std::sscanf(status.c_str() + at, "live IoU %lf BF %lf (5 s), %lf %lf over %ld frames, %ld board-only",
			   &f.recentIou, &f.recentBf, &f.iou, &f.bf, &f.frames, &f.boardOnly) == 6;
}

} // namespace

TEST(LiveScoreDaemon, SimulatedCamerasAreScoredInTheStatusLine)
{
	DaemonProcess daemon;
	const std::string config = daemon.writeFile("depthkey.toml", "[output]\n"
								     "composite_name = \"/dk-live-" + std::to_string(getpid()) +
								     ".composite\"\nlecturer_name = \"/dk-live-" +
								     std::to_string(getpid()) + ".lecturer\"\n");
	ASSERT_TRUE(daemon.start({ "--config", config }));
	ASSERT_TRUE(daemon.waitForNotify("READY=1", 10s)) << daemon.log();
	LiveFigures f;
	depthkey::test::waitUntil(
		[&] {
			daemon.pollNotify();
			const auto &all = daemon.notifications();
			for (auto it = all.rbegin(); it != all.rend(); ++it)
				if (it->find("STATUS=") != std::string::npos)
					return parseLive(*it, f) && f.frames >= 150;
			return false;
		},
		60s, 100ms);
	// 150 frames: the last 5 s then lie past the first seconds, where the
	// colour models are still being learnt (a slow build, SAN=1, keys few
	// frames a second; a window of the first 60 scored 0.35 in 1 of 4 runs).
	ASSERT_GE(f.frames, 150) << daemon.log();
	// The simulated lecturer keyed by the shipped pipeline: far from
	// nothing, at most perfect (a figure that is computed, not copied).
	// Only a floor here: on a slow build (SAN=1) frames are shed and scored
	// as the stale layer the student keeps seeing, so the figure measures
	// the box's speed too (0.35-0.49 seen there, 0.9+ on the native build);
	// live against offline is `make live-share`'s test.
	EXPECT_GT(f.iou, 0.2);
	EXPECT_LE(f.iou, 1.0);
	EXPECT_GT(f.bf, 0.1);
	EXPECT_GT(f.recentIou, 0.2);
	ASSERT_EQ(daemon.signal(SIGTERM), 0);
	EXPECT_NE(daemon.waitExit(5s), -1);
}

TEST(LiveScoreDaemon, RealCamerasAreNotScored)
{
	// A replay of a sequence without mask/ is a camera that knows no truth.
	DaemonProcess daemon;
	const std::string seq = daemon.dir() + "/seq";
	int status;
	const std::string out = run(depthkey::test::binDir() + "/depthkey-eval --sim 1 --frames 20 --save-sequence " +
					    seq + " && rm -r " + seq + "/mask " + seq + "/mask.txt",
				    status);
	ASSERT_EQ(status, 0) << out;
	const std::string config = daemon.writeFile(
		"depthkey.toml", "[colour]\nbackend = \"replay\"\n[depth]\nbackend = \"replay\"\n[replay]\npath = \"" +
					 seq + "\"\n[output]\ncomposite_name = \"/dk-nolive-" + std::to_string(getpid()) +
					 ".composite\"\nlecturer_name = \"/dk-nolive-" + std::to_string(getpid()) +
					 ".lecturer\"\n");
	ASSERT_TRUE(daemon.start({ "--config", config }));
	ASSERT_TRUE(daemon.waitForNotify("READY=1", 10s)) << daemon.log();
	depthkey::test::waitUntil(
		[&] {
			daemon.pollNotify();
			return daemon.countNotify("STATUS=") >= 3;
		},
		10s, 100ms);
	ASSERT_GE(daemon.countNotify("STATUS="), 3) << daemon.log();
	EXPECT_EQ(daemon.countNotify("live IoU"), 0);
	ASSERT_EQ(daemon.signal(SIGTERM), 0);
	EXPECT_NE(daemon.waitExit(5s), -1);
}

// 60 s at 640x480, 25 fps, on 35 % of one core: keying today needs more
// than that per frame, so frames are shed, and a shed frame scores the
// stale layer the student goes on seeing. What is seen must still score as
// depthkey-eval's keying of the same frames. It fails today: on 7 December
// (a busy host) keying took 90 ms a frame, 479 frames were shed, and live
// IoU was 0.845 (BF 0.631) against offline 0.900 (BF 0.891); 0 board-only.
TEST(LiveScoreDaemon, UnderACpuShareLiveIsOffline)
{
	const char *asked = std::getenv("DEPTHKEY_LIVE_SHARE");
	if (!asked || std::string(asked) != "1")
		GTEST_SKIP() << "a minute and more: make live-share (DEPTHKEY_LIVE_SHARE=1)";
	int status;
	const std::string out = run("sh " + depthkey::test::sourceDir() + "/tests/process/live_vs_offline.sh " +
					    depthkey::test::binDir() + " 1 35 640 480 25 60",
				    status);
	if (status == 77)
		GTEST_SKIP() << out;
	ASSERT_EQ(status, 0) << out;
	const std::string line = lastLine(out);
	std::printf("%s\n", line.c_str());
	double offline = -1, live = -1;
	long liveFrames = -1, boardOnly = -1, shed = -1;
	ASSERT_EQ(std::sscanf(line.c_str(),
			      "live seed=1 share=35 size=640x480 fps=25 frames=1500 offline_iou=%lf offline_bf=%*f "
			      "live_iou=%lf live_bf=%*f live_frames=%ld board_only=%ld shed=%ld",
			      &offline, &live, &liveFrames, &boardOnly, &shed),
		  5)
		<< out;
	EXPECT_GE(liveFrames, 100) << "frames were published and scored";
	EXPECT_NEAR(live, offline, 0.02);
	EXPECT_EQ(boardOnly, 0) << "frames that showed the board alone while both cameras streamed";
}
