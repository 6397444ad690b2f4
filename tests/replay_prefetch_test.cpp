// Issue 29 §2: the replay's frames read and decoded ahead on a thread of
// their own (hal/replay/replay_prefetch.hpp). What is played must be what
// the synchronous read gave, in the same order, bad files and loops
// included; a stop or a detach while the thread reads must neither crash
// nor hand an old frame to the next attach; no more than kAhead frames a
// stream are read ahead.
#include "hal/replay/replay_cameras.hpp"
#include "hal/replay/replay_prefetch.hpp"
#include "tests/hostile_files.hpp"
#include "tests/replay_recording.hpp"
#include "tests/wait_until.hpp"

#include <dirent.h>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <vector>

using namespace depthkey;
using depthkey::test::listed;
using depthkey::test::lostReports;
using depthkey::test::record;
using depthkey::test::ScratchDir;

namespace {

// One frame as a camera handler got it, or as the synchronous read gives it.
struct Played {
	char stream = 'c';
	uint64_t sequence = 0, timestampNs = 0;
	RgbImage rgb;
	Gray8Image truth;
	Gray16Image depth;
};

// Threads of this process named name (/proc/self/task/*/comm).
int threadsNamed(const std::string &name)
{
	int n = 0;
	for (const auto &task : std::filesystem::directory_iterator("/proc/self/task")) {
		std::string comm;
		std::getline(std::ifstream(task.path() / "comm"), comm);
		n += comm == name;
	}
	return n;
}

// What ReplayTimeline played before the reader thread: each pass the
// streams merged by timestamp (depth first on a tie), a frame that cannot be
// read left out, sequences and timestamps moved on by a pass a loop.
std::vector<Played> readSynchronously(const std::string &dir, int passes)
{
	SequenceReader reader;
	EXPECT_EQ(reader.open(dir), 0) << reader.describeError();
	const auto &colour = reader.colour(), &depth = reader.depth();
	const uint64_t first = std::min(colour.front().timestampNs, depth.front().timestampNs);
	const uint64_t last = std::max(colour.back().timestampNs, depth.back().timestampNs);
	const uint64_t colourPeriod = (colour.back().timestampNs - colour.front().timestampNs) / (colour.size() - 1);
	const uint64_t length = last - first + colourPeriod;
	std::vector<Played> out;
	for (int pass = 0; pass < passes; ++pass) {
		for (size_t c = 0, d = 0; c < colour.size() || d < depth.size();) {
			Played p;
			const bool depthNext = d < depth.size() &&
					       (c == colour.size() || depth[d].timestampNs <= colour[c].timestampNs);
			if (depthNext) {
				DepthFrame f;
				if (reader.readDepth(d++, f) < 0)
					continue;
				p = { 'd', f.sequence + pass * depth.size(), f.timestampNs + pass * length, {}, {}, f.depthMm };
			} else {
				ColourFrame f;
				Gray8Image mask;
				if (reader.readColour(c, f) < 0 || reader.readMask(c, mask) < 0) {
					c++;
					continue;
				}
				c++;
				p = { 'c', f.sequence + pass * colour.size(), f.timestampNs + pass * length, f.rgb, mask, {} };
			}
			out.push_back(std::move(p));
		}
	}
	return out;
}

} // namespace

// The reader thread against what the loop read itself before: a bad colour
// file, a bad depth file, three passes of a looping replay played as fast as
// the thread reads (the loop is always waiting for it).
TEST(ReplayPrefetch, PlaysWhatTheSynchronousReadGaveInItsOrder)
{
	ScratchDir scratch;
	const std::string dir = scratch.path();
	record(dir, 10, 4);
	std::ofstream(dir + "/" + listed(dir, true)[6].file) << "not a png"; // corrupt
	std::filesystem::remove(dir + "/" + listed(dir, false)[1].file);    // missing
	const std::vector<Played> expected = readSynchronously(dir, 3);
	ASSERT_EQ(expected.size(), 3u * (9 + 3));

	auto timeline = std::make_shared<ReplayTimeline>(ReplaySettings{ dir, false, true }, 16, 12);
	ReplayColourCamera colour(timeline);
	ReplayDepthCamera depth(timeline);
	EventLoop events;
	ASSERT_EQ(events.open(), 0);
	std::vector<Played> got;
	std::vector<DeviceStatus> colourReports, depthReports;
	auto played = [&](Played p) {
		got.push_back(std::move(p));
		if (got.size() == expected.size())
			events.exit(0);
	};
	ASSERT_EQ(colour.start(
			  events,
			  [&](const ColourFrame &f) { played({ 'c', f.sequence, f.timestampNs, f.rgb, f.truth, {} }); },
			  [&](const DeviceStatus &s) { colourReports.push_back(s); }),
		  0);
	ASSERT_EQ(depth.start(
			  events,
			  [&](const DepthFrame &f) { played({ 'd', f.sequence, f.timestampNs, {}, {}, f.depthMm }); },
			  [&](const DeviceStatus &s) { depthReports.push_back(s); }),
		  0);
	EventSource guard;
	events.addTimer(10'000'000, [&] { events.exit(1); }, guard);
	ASSERT_EQ(events.run(), 0) << "played " << got.size() << " of " << expected.size();
	ASSERT_EQ(got.size(), expected.size());
	for (size_t k = 0; k < got.size(); ++k) {
		SCOPED_TRACE("frame " + std::to_string(k) + " played");
		EXPECT_EQ(got[k].stream, expected[k].stream);
		EXPECT_EQ(got[k].sequence, expected[k].sequence);
		EXPECT_EQ(got[k].timestampNs - got[0].timestampNs, expected[k].timestampNs - expected[0].timestampNs);
		EXPECT_TRUE(got[k].rgb == expected[k].rgb);
		EXPECT_TRUE(got[k].truth == expected[k].truth);
		EXPECT_TRUE(got[k].depth == expected[k].depth);
	}
	// Found bad once, skipped (and counted) on the later passes.
	EXPECT_EQ(lostReports(colourReports), 1);
	EXPECT_EQ(lostReports(depthReports), 1);
	EXPECT_EQ(colour.status().droppedFrames, 3u);
	EXPECT_EQ(depth.status().droppedFrames, 3u);
}

// A reload stops both cameras from a frame handler while the thread is
// reading ahead, and starts them again: the folder plays from its start,
// not from frames read for the old start. A camera detached alone and
// attached again starts its own stream afresh. The thread is there while
// the replay plays and gone when the timeline is.
TEST(ReplayPrefetch, AStopOrDetachWhileTheThreadReadsStartsAfresh)
{
	ScratchDir scratch;
	const std::string dir = scratch.path();
	record(dir, 30, 12, 320, 240);
	auto timeline = std::make_shared<ReplayTimeline>(ReplaySettings{ dir, false, true }, 320, 240);
	auto colour = std::make_unique<ReplayColourCamera>(timeline);
	auto depth = std::make_unique<ReplayDepthCamera>(timeline);
	timeline.reset(); // the cameras own it, as in the daemon
	EventLoop events;
	ASSERT_EQ(events.open(), 0);
	EventSource restart;
	std::vector<int> firstColourAfterStart, firstDepthAfterAttach;
	int colourSinceStart = 0, depthSinceAttach = 0, starts = 0, replayThreads = 0;
	std::function<void()> startDepth, startBoth;
	// Called by the handler, which the stop below destroys: this outlives it.
	auto played = [&](const ColourFrame &f) {
		if (colourSinceStart++ == 0)
			firstColourAfterStart.push_back(f.rgb.at(0, 0).r);
		replayThreads = std::max(replayThreads, threadsNamed("dk-replay"));
		if (colourSinceStart == 3 && starts % 2 == 0) { // depth alone, attached again at once
			depth->stop();
			startDepth();
		}
		if (colourSinceStart == 7) { // a reload: everything stops, then starts again
			colour->stop();
			depth->stop();
			if (starts == 4)
				events.exit(0);
			else
				events.addTimer(0, startBoth, restart);
		}
	};
	auto onDepth = [&](const DepthFrame &f) {
		if (depthSinceAttach++ == 0)
			firstDepthAfterAttach.push_back(f.depthMm.at(0, 0) - 1000);
	};
	startDepth = [&] {
		depthSinceAttach = 0;
		ASSERT_EQ(depth->start(events, onDepth, [](const DeviceStatus &) {}), 0);
	};
	startBoth = [&] {
		starts++;
		colourSinceStart = 0;
		ASSERT_EQ(colour->start(events, [&played](const ColourFrame &f) { played(f); }, [](const DeviceStatus &) {}),
			  0);
		startDepth();
	};
	startBoth();
	EventSource guard;
	events.addTimer(20'000'000, [&] { events.exit(1); }, guard);
	ASSERT_EQ(events.run(), 0) << "the replay stalled after " << starts << " starts";
	EXPECT_EQ(firstColourAfterStart, std::vector<int>(4, 0)) << "each start plays colour frame 0 first";
	EXPECT_EQ(firstDepthAfterAttach, std::vector<int>(4 + 2, 0)) << "each attach plays depth frame 0 first";
	EXPECT_EQ(replayThreads, 1);
	// Joined, the thread may still be listed a moment (under qemu-user the
	// host thread behind it outlived the join: 1 of 1 arm64 runs).
	const auto gone = [] { return threadsNamed("dk-replay") == 0; };
	EXPECT_TRUE(depthkey::test::waitUntil(gone, std::chrono::seconds(3))) << "stopped with both cameras";

	EventLoop again; // sd-event takes no source once it has exited
	ASSERT_EQ(again.open(), 0);
	ASSERT_EQ(colour->start(again, [](const ColourFrame &) {}, [](const DeviceStatus &) {}), 0);
	EXPECT_EQ(colour->status().state, DeviceState::Streaming) << colour->status().detail;
	EXPECT_EQ(threadsNamed("dk-replay"), 1);
	colour.reset(); // the timeline goes with its last camera, its thread reading
	depth.reset();
	EXPECT_TRUE(depthkey::test::waitUntil(gone, std::chrono::seconds(3)));
}

// The bound: with nobody taking frames the thread reads kAhead of a stream
// and waits. Files removed after that are found missing only for the frames
// after those, read into the slots freed, the same slots again.
TEST(ReplayPrefetch, ReadsKAheadFramesAndReusesTheirSlots)
{
	ScratchDir scratch;
	const std::string dir = scratch.path();
	record(dir, 8, 0);
	SequenceReader reader;
	ASSERT_EQ(reader.open(dir), 0);
	EventLoop events;
	ASSERT_EQ(events.open(), 0);
	ReplayPrefetch prefetch;
	EventSource quiet, guard;
	bool removed = false;
	std::vector<const void *> slots;
	size_t next = 0;
	// After the removal, the frames read from then on: missing files, in the slots freed.
	auto takeMissing = [&] {
		while (next < 2 * ReplayPrefetch::kAhead) {
			PrefetchedFrame<ColourFrame> *f = prefetch.take<ColourFrame>();
			if (!f)
				return; // not read yet
			EXPECT_EQ(f->index, next);
			EXPECT_EQ(f->result, -ENOENT) << "frame " << next << " read before its slot was free";
			EXPECT_EQ(f, slots.at(next % ReplayPrefetch::kAhead));
			prefetch.release(f);
			next++;
		}
		events.exit(0);
	};
	// Once the thread has been quiet for 300 ms, it has read all it may.
	auto whenQuiet = [&] {
		removed = true;
		std::filesystem::remove_all(dir + "/rgb");
		for (; next < ReplayPrefetch::kAhead; ++next) {
			PrefetchedFrame<ColourFrame> *f = prefetch.take<ColourFrame>();
			if (!f) {
				ADD_FAILURE() << "frame " << next << " not read ahead";
				return events.exit(1);
			}
			EXPECT_EQ(f->index, next);
			EXPECT_EQ(f->result, 0) << f->error;
			EXPECT_EQ(f->frame.rgb.at(0, 0).r, next);
			slots.push_back(f);
			prefetch.release(f);
		}
		takeMissing();
	};
	auto onRead = [&] {
		if (removed)
			takeMissing();
		else
			events.addTimer(300'000, whenQuiet, quiet);
	};
	ASSERT_EQ(prefetch.start(events, reader, 16, 12, false, onRead), 0);
	events.addTimer(300'000, whenQuiet, quiet);
	prefetch.restart<ColourFrame>(std::vector<bool>(reader.colour().size(), false));
	events.addTimer(10'000'000, [&] { events.exit(2); }, guard);
	EXPECT_EQ(events.run(), 0);
	EXPECT_EQ(next, 2 * ReplayPrefetch::kAhead);
}
