// Starts the real depthkeyd on simulated devices and checks what systemd and
// the recorder would see: the notify protocol, frames in shared memory,
// reload with a broken config, clean stop.
#include "hal/depthkey_shm.h"
#include "hal/recording/sequence_writer.hpp"
#include "tests/process/daemon_process.hpp"
#include "tests/test_paths.hpp"
#include "tests/wait_until.hpp"
#include "tests/shm_test_util.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <glob.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <thread>
#include <vector>

using namespace std::chrono_literals;
using depthkey::test::DaemonProcess;
using depthkey::test::waitUntil;

namespace {

std::string configText(const std::string &prefix, const std::string &extra = "")
{
	return "[colour]\nwidth = 320\nheight = 240\nfps = 25\n"
	       "[output]\ncomposite_name = \"" + prefix + ".composite\"\n"
	       "lecturer_name = \"" + prefix + ".lecturer\"\n" + extra;
}

struct ShmFrame {
	dk_shm_frame_info info{};
	std::vector<uint8_t> pixels;
};

// Opens and reads the newest frame, retrying while the writer starts up.
bool readFrame(const std::string &name, ShmFrame &frame, std::chrono::milliseconds timeout)
{
	return waitUntil(
		[&] {
			dk_shm_reader reader{};
			if (dk_shm_open(name.c_str(), &reader) != 0)
				return false;
			frame.pixels.resize(reader.frame_bytes);
			int ret = dk_shm_read_latest(&reader, frame.pixels.data(), frame.pixels.size(), &frame.info);
			dk_shm_close(&reader);
			return ret == 0;
		},
		timeout, 20ms);
}

// Whether a file matches the shell pattern.
bool matches(const std::string &pattern)
{
	glob_t found{};
	bool any = glob(pattern.c_str(), 0, nullptr, &found) == 0 && found.gl_pathc > 0;
	globfree(&found);
	return any;
}

} // namespace

class DaemonIntegration : public testing::Test
{
protected:
	void SetUp() override
	{
		prefix_ = "/depthkey-it-" + std::to_string(getpid());
		config_ = daemon_.writeFile("depthkey.toml", configText(prefix_));
	}
	void TearDown() override
	{
		depthkey::test::unlinkStreams(prefix_);
	}

	DaemonProcess daemon_;
	std::string prefix_;
	std::string config_;
};

TEST_F(DaemonIntegration, ReadyWatchdogFramesReloadAndStop)
{
	ASSERT_TRUE(daemon_.start({ "--config", config_ }, 300000));
	ASSERT_TRUE(daemon_.waitForNotify("READY=1", 10s)) << daemon_.log();

	// WATCHDOG=1 keeps arriving (every WATCHDOG_USEC / 2 while frames flow).
	int before = daemon_.countNotify("WATCHDOG=1");
	waitUntil(
		[&] {
			daemon_.pollNotify();
			return daemon_.countNotify("WATCHDOG=1") - before >= 3 &&
			       daemon_.countNotify("STATUS=colour sim-colour streaming") >= 1;
		},
		5s);
	EXPECT_GE(daemon_.countNotify("WATCHDOG=1") - before, 3);
	EXPECT_GE(daemon_.countNotify("STATUS=colour sim-colour streaming"), 1);

	// Frames in shared memory: rising frame numbers, online, plausible content.
	ShmFrame first, second;
	ASSERT_TRUE(readFrame(prefix_ + ".composite", first, 2s));
	waitUntil([&] { return readFrame(prefix_ + ".composite", second, 2s) && second.info.frame > first.info.frame; },
		  2s);
	ASSERT_TRUE(readFrame(prefix_ + ".composite", second, 2s));
	EXPECT_GT(second.info.frame, first.info.frame);
	EXPECT_GT(second.info.timestamp_ns, first.info.timestamp_ns);
	EXPECT_EQ(second.info.width, 320u);
	EXPECT_EQ(second.info.height, 240u);
	EXPECT_EQ(second.info.fourcc, DK_SHM_FORMAT_RGB24);
	EXPECT_TRUE(second.info.flags & DK_SHM_FLAG_ONLINE);
	EXPECT_EQ(second.info.online, 1u);

	// The lecturer layer: over a second of frames the simulated lecturer is
	// keyed in somewhere (alpha > 0), and the board is never keyed as a whole.
	// The share varies as he walks, turns and leaves the view, so take the
	// largest seen rather than one frame's.
	size_t mostOpaque = 0, pixels = 0;
	for (int i = 0; i < 10; ++i) {
		ShmFrame lecturer;
		ASSERT_TRUE(readFrame(prefix_ + ".lecturer", lecturer, 2s));
		pixels = lecturer.pixels.size() / 4;
		size_t opaque = 0;
		for (size_t p = 0; p < pixels; ++p)
			opaque += lecturer.pixels[p * 4 + 3] != 0;
		EXPECT_LT(opaque, pixels * 3 / 5) << "frame " << lecturer.info.frame;
		mostOpaque = std::max(mostOpaque, opaque);
		std::this_thread::sleep_for(100ms);
	}
	EXPECT_GT(mostOpaque, pixels / 100);

	// A broken config on SIGHUP is refused, naming file and line; the
	// daemon runs on with the old one.
	daemon_.writeFile("depthkey.toml", configText(prefix_, "[segmentation]\nnear_mm = \"close\"\n"));
	daemon_.pollNotify();
	const int readyBefore = daemon_.countNotify("READY=1");
	ASSERT_EQ(daemon_.signal(SIGHUP), 0);
	ASSERT_TRUE(daemon_.waitForNotify("RELOADING=1", 5s));
	// The reload is over when READY=1 comes again.
	waitUntil(
		[&] {
			daemon_.pollNotify();
			return daemon_.countNotify("READY=1") > readyBefore;
		},
		5s);
	EXPECT_TRUE(daemon_.running());
	EXPECT_NE(daemon_.log().find("depthkey.toml:9:11"), std::string::npos) << daemon_.log();
	ShmFrame third;
	ASSERT_TRUE(readFrame(prefix_ + ".composite", third, 2s));
	EXPECT_GT(third.info.frame, second.info.frame);
	EXPECT_EQ(third.info.width, 320u);

	// A good config is taken: the new resolution appears in shared memory.
	daemon_.writeFile("depthkey.toml",
			  "[colour]\nwidth = 160\nheight = 120\n[output]\ncomposite_name = \"" +
				  prefix_ + ".composite\"\nlecturer_name = \"" + prefix_ + ".lecturer\"\n");
	ASSERT_EQ(daemon_.signal(SIGHUP), 0);
	ShmFrame resized;
	waitUntil([&] { return readFrame(prefix_ + ".composite", resized, 1s) && resized.info.width == 160; }, 5s,
		  50ms);
	EXPECT_EQ(resized.info.width, 160u);
	EXPECT_EQ(resized.info.height, 120u);

	// SIGTERM: STOPPING=1, exit status 0.
	ASSERT_EQ(daemon_.signal(SIGTERM), 0);
	int status = daemon_.waitExit(5s);
	ASSERT_NE(status, -1) << "depthkeyd did not stop";
	EXPECT_TRUE(WIFEXITED(status));
	EXPECT_EQ(WEXITSTATUS(status), 0);
	daemon_.pollNotify();
	EXPECT_GE(daemon_.countNotify("STOPPING=1"), 1);
}

TEST_F(DaemonIntegration, CheckConfigReportsErrorsAndExitStatus)
{
	std::string bad = daemon_.writeFile("bad.toml", "[segmentation]\nnear_mm = 9000\nfrobnicate = 1\n");
	ASSERT_TRUE(daemon_.start({ "--check-config", bad }));
	int status = daemon_.waitExit(5s);
	ASSERT_TRUE(WIFEXITED(status));
	EXPECT_EQ(WEXITSTATUS(status), 1);
	std::string log = daemon_.log();
	EXPECT_NE(log.find("bad.toml:2:11"), std::string::npos) << log;
	EXPECT_NE(log.find("segmentation.frobnicate"), std::string::npos) << log;
}

TEST_F(DaemonIntegration, SigintStopsCleanly)
{
	ASSERT_TRUE(daemon_.start({ "--config", config_ }));
	ASSERT_TRUE(daemon_.waitForNotify("READY=1", 10s)) << daemon_.log();
	ASSERT_EQ(daemon_.signal(SIGINT), 0);
	int status = daemon_.waitExit(5s);
	ASSERT_TRUE(WIFEXITED(status));
	EXPECT_EQ(WEXITSTATUS(status), 0);
}

// A corrupt calibration file is refused with file:line; the daemon runs on,
// mapping by plain scaling, and says so.
TEST_F(DaemonIntegration, CorruptCalibrationIsRefusedWithFileAndLine)
{
	std::string calibration = daemon_.writeFile("calibration.toml", "format = 1\n[calibration]\nmodel = 7\n");
	config_ = daemon_.writeFile("depthkey.toml",
				    configText(prefix_, "[mapping]\ncalibration_file = \"" + calibration + "\"\n"));
	ASSERT_TRUE(daemon_.start({ "--config", config_ }));
	ASSERT_TRUE(daemon_.waitForNotify("READY=1", 10s)) << daemon_.log();
	EXPECT_TRUE(daemon_.running());
	std::string log = daemon_.log();
	// The first problem in file order: [calibration] on line 2 lacks keys.
	EXPECT_NE(log.find("calibration.toml:2:"), std::string::npos) << log;
	EXPECT_NE(log.find("plain scaling"), std::string::npos) << log;
	ASSERT_EQ(daemon_.signal(SIGTERM), 0);
	int status = daemon_.waitExit(5s);
	ASSERT_TRUE(WIFEXITED(status));
	EXPECT_EQ(WEXITSTATUS(status), 0);
}

namespace {

int countLines(const std::string &path, char skipIfFirst)
{
	FILE *f = std::fopen(path.c_str(), "r");
	if (!f)
		return -1;
	int n = 0;
	char line[512];
	while (std::fgets(line, sizeof(line), f))
		n += line[0] != skipIfFirst;
	std::fclose(f);
	return n;
}

} // namespace

// --record writes what the cameras deliver; the replay backends play it
// back so that the daemon runs on it as on live cameras; --preview writes
// stage images.
TEST_F(DaemonIntegration, RecordThenReplayWithPreviews)
{
	std::string recording = daemon_.dir() + "/recording";
	std::string previews = daemon_.dir() + "/previews";
	ASSERT_TRUE(daemon_.start({ "--config", config_, "--record", recording, "--preview", previews }));
	ASSERT_TRUE(daemon_.waitForNotify("READY=1", 10s)) << daemon_.log();
	const char *const stages[] = { "colour", "depth", "alpha", "composite" };
	auto previewWritten = [&](const char *stage) { return matches(previews + "/frame*-" + stage + ".png"); };
	// Recording until the folder holds enough frames and the first keyed
	// frame's stage images are there.
	waitUntil(
		[&] {
			return countLines(recording + "/rgb.txt", '#') >= 15 &&
			       countLines(recording + "/depth.txt", '#') >= 5 &&
			       std::all_of(std::begin(stages), std::end(stages), previewWritten);
		},
		10s, 50ms);
	ASSERT_EQ(daemon_.signal(SIGTERM), 0);
	ASSERT_NE(daemon_.waitExit(5s), -1);
	int colourFrames = countLines(recording + "/rgb.txt", '#');
	EXPECT_GE(colourFrames, 15) << daemon_.log();
	EXPECT_GE(countLines(recording + "/depth.txt", '#'), 5);
	EXPECT_EQ(countLines(recording + "/amplitude.txt", '#'), countLines(recording + "/depth.txt", '#'));
	struct stat st;
	EXPECT_EQ(stat((recording + "/rgb/000001.png").c_str(), &st), 0);
	for (const char *stage : stages)
		EXPECT_TRUE(previewWritten(stage)) << stage << "\n" << daemon_.log();

	DaemonProcess replay;
	std::string replayConfig = replay.writeFile("depthkey.toml",
					"[colour]\nbackend = \"replay\"\nwidth = 320\nheight = 240\n"
					"[depth]\nbackend = \"replay\"\n"
					"[output]\ncomposite_name = \"" + prefix_ + ".composite\"\n"
					"lecturer_name = \"" + prefix_ + ".lecturer\"\n"
					"[replay]\npath = \"" + recording + "\"\n");
	ASSERT_TRUE(replay.start({ "--config", replayConfig }));
	ASSERT_TRUE(replay.waitForNotify("READY=1", 10s)) << replay.log();
	waitUntil(
		[&] {
			replay.pollNotify();
			return replay.countNotify("STATUS=colour replay-colour streaming") >= 1;
		},
		5s);
	EXPECT_GE(replay.countNotify("STATUS=colour replay-colour streaming"), 1) << replay.log();
	// Keyed frames from both replayed cameras. The first frames out may be
	// NO SIGNAL ones, from before the first colour frame was keyed (CI's
	// sanitizer build read one): wait for an online frame.
	ShmFrame frame;
	waitUntil([&] { return readFrame(prefix_ + ".composite", frame, 1s) && (frame.info.flags & DK_SHM_FLAG_ONLINE); },
		  5s, 20ms);
	EXPECT_TRUE(frame.info.flags & DK_SHM_FLAG_ONLINE) << replay.log();
	ASSERT_EQ(replay.signal(SIGTERM), 0);
	EXPECT_NE(replay.waitExit(5s), -1);
}

// Issue 31 point 14: a replay whose colour size is not [colour]'s published
// nothing (0 frames to the recorder in 12 s) while the status said 24 fps,
// and sent neither READY=1 nor WATCHDOG=1. Its colour frames are refused now,
// naming the size, and the recorder gets NO SIGNAL frames at [colour]'s size,
// which READY=1 and the watchdog follow.
TEST_F(DaemonIntegration, AReplayOfAnotherSizeSendsNoSignalReadyAndWatchdog)
{
	const std::string recording = daemon_.dir() + "/small";
	{
		depthkey::SequenceWriter writer;
		ASSERT_EQ(writer.open(recording), 0) << writer.describeError();
		for (int i = 0; i < 25; ++i) {
			depthkey::ColourFrame colour;
			colour.rgb = depthkey::RgbImage(160, 120, depthkey::Rgb8{ uint8_t(i * 10), 90, 40 });
			colour.timestampNs = 1'000'000'000 + uint64_t(i) * 40'000'000;
			colour.sequence = i + 1;
			ASSERT_EQ(writer.writeColour(colour), 0) << writer.describeError();
		}
	}
	std::string config = daemon_.writeFile("replay.toml",
					       "[colour]\nbackend = \"replay\"\nwidth = 320\nheight = 240\n"
					       "[output]\ncomposite_name = \"" + prefix_ + ".composite\"\n"
					       "lecturer_name = \"" + prefix_ + ".lecturer\"\n"
					       "[replay]\npath = \"" + recording + "\"\n");
	ASSERT_TRUE(daemon_.start({ "--config", config }, 300000));
	ASSERT_TRUE(daemon_.waitForNotify("READY=1", 10s)) << daemon_.log(); // degraded: after 5 s
	int before = daemon_.countNotify("WATCHDOG=1");
	waitUntil(
		[&] {
			daemon_.pollNotify();
			return daemon_.countNotify("WATCHDOG=1") - before >= 3;
		},
		5s);
	EXPECT_GE(daemon_.countNotify("WATCHDOG=1") - before, 3) << daemon_.log();
	ShmFrame frame;
	ASSERT_TRUE(readFrame(prefix_ + ".composite", frame, 2s));
	EXPECT_EQ(frame.info.width, 320u);
	EXPECT_FALSE(frame.info.flags & DK_SHM_FLAG_COLOUR_OK) << "a NO SIGNAL frame";
	EXPECT_NE(daemon_.log().find("160x120, not [colour]'s 320x240"), std::string::npos) << daemon_.log();
	ASSERT_EQ(daemon_.signal(SIGTERM), 0);
	EXPECT_NE(daemon_.waitExit(5s), -1);
}

// depthkey-calibrate --sim calibrates the simulated room in one go: its file's
// [board] puts the daemon in board geometry with board.homography_file
// empty, and the board's picture teaches the board model.
TEST_F(DaemonIntegration, TakesTheBoardFromTheCalibrationFile)
{
	const std::string calibration = daemon_.writeFile("calibration.toml", "");
	ASSERT_EQ(std::system((depthkey::test::binDir() + "/depthkey-calibrate --sim --output " + calibration +
			       " >/dev/null 2>&1").c_str()),
		  0);
	const std::string config = daemon_.writeFile(
		"board.toml", "[colour]\nwidth = 640\nheight = 480\nfps = 25\n[mapping]\ncalibration_file = \"" +
				      calibration + "\"\n[output]\ncomposite_name = \"" + prefix_ +
				      ".composite\"\nlecturer_name = \"" + prefix_ + ".lecturer\"\n");
	ASSERT_TRUE(daemon_.start({ "--config", config }, 300000));
	ASSERT_TRUE(daemon_.waitForNotify("READY=1", 10s)) << daemon_.log();
	ShmFrame frame;
	EXPECT_TRUE(waitUntil([&] { return readFrame(prefix_ + ".composite", frame, 1s) && frame.info.width == 1920; },
			      5s, 50ms))
		<< daemon_.log();
	EXPECT_EQ(frame.info.width, 1920u);
	EXPECT_EQ(frame.info.height, 780u) << "the simulated display's shape";
	EXPECT_NE(daemon_.log().find("board calibration from mapping.calibration_file's [board]"), std::string::npos)
		<< daemon_.log();
}
