// Issue 31, points 11 and 14: the replay backends on hostile folders. A bad
// file makes its own camera Lost, naming it; colour of another size than
// [colour] is refused, and the daemon publishes NO SIGNAL instead of
// nothing; a depth-only recording plays; frames dropped are counted; a
// folder of bad files changes the status once, not once a frame.
#include "daemon/daemon.hpp"
#include "daemon/frame_pairing.hpp"
#include "hal/depthkey_shm.h"
#include "hal/fake_frame_sink.hpp"
#include "hal/recording/sequence_reader.hpp"
#include "hal/recording/sequence_writer.hpp"
#include "hal/replay/replay_cameras.hpp"
#include "hal/sim/sim_sequence.hpp"
#include "tests/hostile_files.hpp"
#include "tests/replay_recording.hpp"

#include <csignal>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <vector>

using namespace depthkey;
using depthkey::test::ScratchDir;
using depthkey::test::listed;
using depthkey::test::lostReports;
using depthkey::test::record;

namespace {

struct Played {
	std::vector<DeviceStatus> colourReports, depthReports;
	int colourFrames = 0, depthFrames = 0;
	DeviceStatus colourEnd, depthEnd; // each camera's status() at the end
};

bool reportsMention(const std::vector<DeviceStatus> &reports, const std::string &text)
{
	for (const DeviceStatus &s : reports)
		if (s.detail.find(text) != std::string::npos)
			return true;
	return false;
}

// Plays dir as fast as it goes, both cameras attached, until each reported
// the end of the recording (loop = false) or `enough` says so; 10 s at most.
Played play(const std::string &dir, int colourWidth, int colourHeight, bool loop,
	    const std::function<bool(const Played &)> &enough = nullptr)
{
	auto timeline = std::make_shared<ReplayTimeline>(ReplaySettings{ dir, false, loop }, colourWidth, colourHeight);
	ReplayColourCamera colour(timeline);
	ReplayDepthCamera depth(timeline);
	EventLoop events;
	EXPECT_EQ(events.open(), 0);
	Played p;
	bool colourEnded = false, depthEnded = false;
	auto check = [&] {
		if ((colourEnded && depthEnded) || (enough && enough(p)))
			events.exit(0);
	};
	auto ended = [&](const DeviceStatus &s) { return s.state == DeviceState::Lost && s.error == -ENODATA; };
	colour.start(
		events, [&](const ColourFrame &) { p.colourFrames++; check(); },
		[&](const DeviceStatus &s) {
			p.colourReports.push_back(s);
			colourEnded = colourEnded || ended(s);
			check();
		});
	depth.start(
		events, [&](const DepthFrame &) { p.depthFrames++; check(); },
		[&](const DeviceStatus &s) {
			p.depthReports.push_back(s);
			depthEnded = depthEnded || ended(s);
			check();
		});
	EventSource guard;
	events.addTimer(10'000'000, [&] { events.exit(1); }, guard);
	EXPECT_EQ(events.run(), 0) << "the replay did not reach its end";
	p.colourEnd = colour.status();
	p.depthEnd = depth.status();
	return p;
}

} // namespace

// Point 11: both cameras used to share one status, so both named the
// colour file when it was missing and the depth file when it was bad.
TEST(ReplayTimeline, ABadFileLosesItsOwnCameraAndNamesIt)
{
	ScratchDir scratch;
	const std::string dir = scratch.path();
	record(dir, 10, 4);
	const std::string colourFile = listed(dir, true)[4].file, depthFile = listed(dir, false)[2].file;
	std::filesystem::remove(dir + "/" + colourFile);
	std::filesystem::copy_file(dir + "/mask/000001.png", dir + "/" + depthFile,
				   std::filesystem::copy_options::overwrite_existing); // 8-bit grey

	Played p = play(dir, 16, 12, false);
	EXPECT_EQ(p.colourFrames, 9);
	EXPECT_EQ(p.depthFrames, 3);
	EXPECT_TRUE(reportsMention(p.colourReports, colourFile));
	EXPECT_TRUE(reportsMention(p.depthReports, depthFile + ": is not 16-bit grey"));
	EXPECT_FALSE(reportsMention(p.colourReports, depthFile)) << "colour blamed for the depth file";
	EXPECT_FALSE(reportsMention(p.depthReports, colourFile)) << "depth blamed for the colour file";
	EXPECT_EQ(p.colourEnd.droppedFrames, 1u);
	EXPECT_EQ(p.depthEnd.droppedFrames, 1u);
}

// Point 14: colour of another size than [colour] went to outputs made for
// [colour]'s size, which refused every frame: nothing was published.
TEST(ReplayTimeline, ColourOfAnotherSizeIsRefusedNamingTheFileAndBothSizes)
{
	ScratchDir scratch;
	const std::string dir = scratch.path();
	record(dir, 6, 3, 16, 12);
	Played p = play(dir, 32, 24, false);
	EXPECT_EQ(p.colourFrames, 0);
	EXPECT_EQ(p.depthFrames, 3) << "depth plays on";
	ASSERT_FALSE(p.colourReports.empty());
	const DeviceStatus &lost = p.colourReports.front().state == DeviceState::Lost ? p.colourReports.front()
										       : p.colourReports.at(1);
	EXPECT_EQ(lost.state, DeviceState::Lost);
	EXPECT_NE(lost.detail.find(listed(dir, true)[0].file + ": 16x12, not [colour]'s 32x24"), std::string::npos)
		<< lost.detail;
	EXPECT_EQ(p.colourEnd.droppedFrames, 6u);
	EXPECT_EQ(lostReports(p.depthReports), 1) << "depth: only its end";
}

// Point 14: with nothing for the colour camera the timer was never armed,
// and the depth frames never came.
TEST(ReplayTimeline, ADepthOnlyRecordingPlaysItsDepth)
{
	ScratchDir scratch;
	const std::string dir = scratch.path();
	record(dir, 0, 5);
	Played p = play(dir, 16, 12, false);
	EXPECT_EQ(p.depthFrames, 5);
	EXPECT_EQ(p.colourFrames, 0);
	EXPECT_TRUE(reportsMention(p.colourReports, "rgb.txt: no colour frames recorded"));
}

// Point 14: a depth frame with its predecessor's timestamp was passed on and
// dropped by the pairing, counted nowhere.
TEST(ReplayTimeline, RepeatedTimestampsAreDroppedAndCounted)
{
	ScratchDir scratch;
	const std::string dir = scratch.path();
	record(dir, 5, 4);
	for (const char *optional : { "/amplitude.txt", "/intensity.txt" })
		std::filesystem::remove(dir + optional);
	std::vector<SequenceEntry> depth = listed(dir, false);
	std::ofstream index(dir + "/depth.txt");
	for (size_t i = 0; i < depth.size(); ++i) // the third stamped as the second
		index << recording::formatTimestamp(depth[i == 2 ? 1 : i].timestampNs) << " " << depth[i].file << "\n";
	index.close();

	Played p = play(dir, 16, 12, false);
	EXPECT_EQ(p.depthFrames, 3);
	EXPECT_EQ(p.depthEnd.droppedFrames, 1u);
	EXPECT_EQ(p.colourFrames, 5);
	EXPECT_EQ(p.colourEnd.droppedFrames, 0u);
}

// The flood: every other colour file missing used to report Lost and
// Streaming again at every frame, on every loop (hundreds of journal lines
// in seconds). Now the camera is Lost once, and the files once found bad
// are skipped on later loops, counted, without a word.
TEST(ReplayTimeline, AFolderOfBadFilesIsReportedOnceNotEveryFrame)
{
	ScratchDir scratch;
	const std::string dir = scratch.path();
	record(dir, 20, 0);
	const std::vector<SequenceEntry> colour = listed(dir, true);
	for (size_t i = 1; i < colour.size(); i += 2)
		std::filesystem::remove(dir + "/" + colour[i].file);
	// Three passes over the recording's ten good frames.
	Played p = play(dir, 16, 12, true, [](const Played &q) { return q.colourFrames >= 30; });
	EXPECT_EQ(p.colourFrames, 30);
	EXPECT_EQ(lostReports(p.colourReports), 1);
	// Streaming at the start, Lost at the first bad file, Streaming again
	// in the second pass, whose known bad files no longer interrupt the
	// good frames.
	EXPECT_LE(p.colourReports.size(), 3u);
	EXPECT_GE(p.colourEnd.droppedFrames, 29u); // 10 a pass, the last pass's last one perhaps not yet
	EXPECT_EQ(p.colourEnd.state, DeviceState::Streaming);
}

// Point 14, in the daemon: the recorder got no frame at all for 12 s from a
// replay of another size (the status said 24 fps). Now it gets NO SIGNAL.
TEST(ReplayTimeline, ADaemonReplayingAnotherSizePublishesNoSignal)
{
	ScratchDir scratch;
	const std::string dir = scratch.path();
	record(dir, 25, 10, 16, 12);
	FakeFrameSink *sink = nullptr;
	DeviceFactory factory; // the real replay cameras
	factory.frameSink = [&sink](const Settings &) {
		auto s = std::make_unique<FakeFrameSink>();
		sink = s.get();
		return s;
	};
	Settings settings;
	settings.colour.backend = settings.depth.backend = "replay";
	settings.colour.width = 32;
	settings.colour.height = 24;
	settings.replay = { dir, true, true };
	settings.preview.listen = "127.0.0.1:0";
	Daemon daemon("unused.toml", {}, factory);
	ASSERT_EQ(daemon.start(settings), 0);
	EventSource stop;
	daemon.loop().addTimer(800'000, [&] { daemon.loop().exit(0); }, stop);
	daemon.run();
	sigset_t all; // Daemon::start blocked the signals it handles
	sigfillset(&all);
	sigprocmask(SIG_UNBLOCK, &all, nullptr);
	ASSERT_NE(sink, nullptr);
	EXPECT_GE(sink->compositeCount(), 5u) << "the recorder heard nothing";
	EXPECT_EQ(sink->noColourCount(), sink->compositeCount()) << "every frame NO SIGNAL";
}

// Point 11: the offset estimator went on measuring across a depth loss ("-269
// ms measured" from a replay whose depth files were bad). The daemon now has
// it forget what it had when depth is lost (Daemon::onDeviceStatus), and no
// estimate stands until enough depth has come after.
TEST(ReplayTimeline, LostDepthRestartsTheOffsetMeasurement)
{
	SimSequence sequence;
	sequence.configure(SimSettings{}, 320, 240, 25, 10);
	Settings settings;
	settings.pairing.offsetAuto = true;
	FramePairing pairing;
	pairing.configure(settings);
	ColourFrame colour;
	GroundTruth truth;
	int depthFrames = 0;
	auto play = [&](int from, int to, bool depth) {
		for (int n = from; n < to; ++n) {
			sequence.frame(uint64_t(n), colour, truth, [&](const DepthFrame &d) {
				if (depth) {
					pairing.addDepth(d);
					depthFrames++;
				}
			});
			pairing.addColour(colour, colour.timestampNs);
			pairing.queue().clear(); // the estimator is the point here, not the queue
		}
	};
	play(0, 25 * 12, true);
	pairing.updateLatency("sim-depth");
	ASSERT_TRUE(pairing.latency().valid) << "12 s of the simulated lecture measure the offset";

	pairing.forgetLatency(); // depth lost
	EXPECT_FALSE(pairing.latency().valid);
	play(25 * 12, 25 * 14, false); // 2 s of colour alone
	depthFrames = 0;
	play(25 * 14, 25 * 16, true); // then 2 s of depth again: 20 frames, fewer than the 30 needed
	pairing.updateLatency("sim-depth");
	EXPECT_LT(depthFrames, int(LatencyEstimator::kMinDepthFrames));
	EXPECT_FALSE(pairing.latency().valid) << "measured across the gap";
}
