#include "daemon/frame_recorder.hpp"
#include "hal/event_loop.hpp"
#include "hal/recording/sequence_reader.hpp"
#include "hal/recording/sequence_writer.hpp"
#include "hal/replay/replay_cameras.hpp"
#include "hal/sim/sim_sequence.hpp"
#include "tests/replay_recording.hpp"
#include "tests/wait_until.hpp"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <vector>

using namespace depthkey;

namespace {

// A fresh folder, removed with everything in it when the test ends.
class TempDir
{
public:
	TempDir()
	{
		char pattern[] = "/tmp/depthkey-rec-XXXXXX";
		const char *dir = mkdtemp(pattern);
		path_ = dir ? dir : "";
	}
	~TempDir()
	{
		if (!path_.empty())
			std::filesystem::remove_all(path_);
	}
	operator std::string() const { return path_; }
	std::string operator+(const char *sub) const { return path_ + sub; }

private:
	std::string path_;
};

// A short simulated sequence: colour frames with truth (in the frame, as
// the simulated camera gives it, and beside it), the depth frames paired
// with them (each once).
struct Recorded {
	std::vector<ColourFrame> colour;
	std::vector<Gray8Image> masks;
	std::vector<DepthFrame> depth;
};

Recorded simulate(int frames)
{
	SimSequence sequence;
	sequence.configure(SimSettings{}, 160, 120, 25, 10);
	Recorded r;
	ColourFrame c;
	GroundTruth t;
	for (uint64_t n = 0; static_cast<int>(r.colour.size()) < frames; ++n) {
		sequence.frame(n, c, t, [&](const DepthFrame &f) { r.depth.push_back(f); });
		c.truth = t.alpha;
		r.colour.push_back(c);
		r.masks.push_back(t.alpha);
	}
	return r;
}

void expectSame(const Recorded &a, const SequenceReader &reader, SequenceReader &mutableReader)
{
	ASSERT_EQ(reader.colour().size(), a.colour.size());
	ASSERT_EQ(reader.depth().size(), a.depth.size());
	ASSERT_TRUE(reader.hasMask());
	for (size_t i = 0; i < a.colour.size(); ++i) {
		ColourFrame c;
		Gray8Image m;
		ASSERT_EQ(mutableReader.readColour(i, c), 0) << mutableReader.describeError();
		ASSERT_EQ(mutableReader.readMask(i, m), 0) << mutableReader.describeError();
		EXPECT_TRUE(c.rgb == a.colour[i].rgb) << i;
		EXPECT_EQ(c.timestampNs, a.colour[i].timestampNs);
		EXPECT_EQ(c.sequence, a.colour[i].sequence);
		EXPECT_TRUE(m == a.masks[i]) << i;
	}
	for (size_t i = 0; i < a.depth.size(); ++i) {
		DepthFrame d;
		ASSERT_EQ(mutableReader.readDepth(i, d), 0) << mutableReader.describeError();
		EXPECT_TRUE(d.depthMm == a.depth[i].depthMm) << i;
		EXPECT_TRUE(d.amplitude == a.depth[i].amplitude) << i;
		EXPECT_TRUE(d.intensity == a.depth[i].intensity) << i;
		EXPECT_EQ(d.timestampNs, a.depth[i].timestampNs);
		EXPECT_EQ(d.sequence, a.depth[i].sequence);
	}
}

} // namespace

TEST(Recording, TimestampsRoundTripToTheNanosecond)
{
	for (uint64_t ns : { 0ull, 1ull, 999999999ull, 1000000000ull, 1234567890123456789ull / 1000 }) {
		uint64_t back = 0;
		ASSERT_TRUE(recording::parseTimestamp(recording::formatTimestamp(ns), back));
		EXPECT_EQ(back, ns);
	}
	uint64_t ns;
	EXPECT_TRUE(recording::parseTimestamp("1305031102.175304", ns)); // TUM's six decimals
	EXPECT_EQ(ns, 1305031102175304000ull);
	EXPECT_FALSE(recording::parseTimestamp("12.x", ns));
	EXPECT_FALSE(recording::parseTimestamp("", ns));
}

// Writes sim into dir and reads it back, each mask written by writeMask
// (the masks apart) or by writeColour from the frame's truth.
static void writeThenRead(const Recorded &sim, bool masksApart)
{
	TempDir temp;
	std::string dir = temp;
	SequenceWriter writer;
	ASSERT_EQ(writer.open(dir), 0) << writer.describeError();
	for (size_t i = 0; i < sim.colour.size(); ++i) {
		ColourFrame colour = sim.colour[i];
		if (masksApart)
			colour.truth = Gray8Image{};
		ASSERT_EQ(writer.writeColour(colour), 0) << writer.describeError();
		if (masksApart) {
			ASSERT_EQ(writer.writeMask(sim.masks[i], colour.timestampNs, colour.sequence), 0);
		}
	}
	for (const DepthFrame &d : sim.depth)
		ASSERT_EQ(writer.writeDepth(d), 0);
	writer.close();
	SequenceReader reader;
	ASSERT_EQ(reader.open(dir), 0) << reader.describeError();
	expectSame(sim, reader, reader);
}

TEST(Recording, WriteThenReadIsBitExact)
{
	writeThenRead(simulate(12), true);
}

// A colour frame that carries its truth (the simulated camera's) is written
// with it: a recording of the simulator replays scored live (issue 29).
TEST(Recording, ColourFrameWithTruthWritesItsMask)
{
	writeThenRead(simulate(6), false);
}

TEST(Recording, DaemonRecorderWritesEverythingItWasGiven)
{
	Recorded sim = simulate(10);
	TempDir temp;
	std::string dir = temp + "/rec";
	FrameRecorder recorder;
	std::string error;
	ASSERT_EQ(recorder.start(dir, 1, error), 0) << error;
	size_t d = 0;
	uint64_t given = 0;
	for (const ColourFrame &c : sim.colour) {
		for (; d < sim.depth.size() && sim.depth[d].timestampNs <= c.timestampNs; ++given)
			recorder.recordDepth(sim.depth[d++]);
		recorder.recordColour(c);
		++given;
		// The worker catches up before the next frame: this test is about
		// content, not drops.
		test::waitUntil([&] { return recorder.written() == given; }, std::chrono::seconds(5));
	}
	while (d < sim.depth.size())
		recorder.recordDepth(sim.depth[d++]);
	recorder.stop();
	EXPECT_EQ(recorder.takeError(), "");
	EXPECT_EQ(recorder.dropped(), 0u);
	SequenceReader reader;
	ASSERT_EQ(reader.open(dir), 0) << reader.describeError();
	ASSERT_EQ(reader.colour().size(), sim.colour.size());
	ColourFrame c;
	ASSERT_EQ(reader.readColour(3, c), 0);
	EXPECT_TRUE(c.rgb == sim.colour[3].rgb);
	DepthFrame df;
	ASSERT_EQ(reader.readDepth(1, df), 0);
	EXPECT_TRUE(df.depthMm == sim.depth[1].depthMm);
	EXPECT_EQ(df.timestampNs, sim.depth[1].timestampNs);
}

TEST(Recording, ReaderErrorsNameTheFileAndLine)
{
	SequenceReader reader;
	EXPECT_EQ(reader.open("/nonexistent/depthkey-seq"), -ENOENT);
	EXPECT_NE(reader.describeError().find("/nonexistent/depthkey-seq"), std::string::npos);

	TempDir temp;
	std::string dir = temp;
	std::ofstream(dir + "/rgb.txt") << "# timestamp filename\n1.0 rgb/000001.png\nbroken\n";
	EXPECT_EQ(reader.open(dir), -EINVAL);
	EXPECT_EQ(reader.describeError(), dir + "/rgb.txt:3: expected \"<seconds> <file>\"");

	std::ofstream(dir + "/rgb.txt") << "1.0 rgb/000001.png\n";
	EXPECT_EQ(reader.open(dir), 0);
	ColourFrame c;
	EXPECT_EQ(reader.readColour(0, c), -ENOENT);
	EXPECT_NE(reader.describeError().find(dir + "/rgb/000001.png"), std::string::npos);
	mkdir((dir + "/rgb").c_str(), 0755);
	std::ofstream(dir + "/rgb/000001.png") << "not a png";
	EXPECT_EQ(reader.readColour(0, c), -EINVAL);
	EXPECT_NE(reader.describeError().find("000001.png"), std::string::npos);

	std::ofstream(dir + "/mask.txt") << "2.0 mask/000001.png\n";
	EXPECT_EQ(reader.open(dir), -EINVAL);
	EXPECT_NE(reader.describeError().find("mask.txt: does not list the same timestamps as rgb.txt"),
		  std::string::npos);
}

// Without amplitude and intensity recorded a depth frame has them zero, in
// the frame's own storage: a replay reads frame after frame into the same
// frames (hal/replay/replay_prefetch.hpp), which used to be given new
// images each time.
TEST(Recording, DepthWithoutAmplitudeReadsZerosIntoItsOwnStorage)
{
	TempDir temp;
	const std::string dir = temp;
	depthkey::test::record(dir, 0, 2);
	for (const char *optional : { "/amplitude.txt", "/intensity.txt" })
		std::filesystem::remove(dir + optional);
	SequenceReader reader;
	ASSERT_EQ(reader.open(dir), 0) << reader.describeError();
	DepthFrame frame;
	frame.amplitude = frame.intensity = Gray16Image(8, 6, 7);
	const uint16_t *amplitude = frame.amplitude.data(), *intensity = frame.intensity.data();
	ASSERT_EQ(reader.readDepth(1, frame), 0) << reader.describeError();
	EXPECT_TRUE(frame.amplitude == Gray16Image(8, 6, 0));
	EXPECT_TRUE(frame.intensity == Gray16Image(8, 6, 0));
	EXPECT_EQ(frame.amplitude.data(), amplitude);
	EXPECT_EQ(frame.intensity.data(), intensity);
}

TEST(Recording, ReplayCamerasPlayTheRecordingInOrder)
{
	Recorded sim = simulate(15);
	TempDir temp;
	std::string dir = temp;
	SequenceWriter writer;
	ASSERT_EQ(writer.open(dir), 0);
	for (const ColourFrame &c : sim.colour)
		writer.writeColour(c);
	for (const DepthFrame &d : sim.depth)
		writer.writeDepth(d);
	writer.close();

	ReplaySettings settings{ dir, false, false }; // as fast as possible, once
	auto timeline = std::make_shared<ReplayTimeline>(settings);
	ReplayColourCamera colour(timeline);
	ReplayDepthCamera depth(timeline);
	EventLoop loop;
	ASSERT_EQ(loop.open(), 0);
	std::vector<ColourFrame> gotColour;
	std::vector<DepthFrame> gotDepth;
	std::string order;
	bool ended = false;
	auto onStatus = [&](const DeviceStatus &s) {
		if (s.state == DeviceState::Lost && s.error == -ENODATA && !ended) {
			ended = true;
			loop.exit(0);
		}
	};
	ASSERT_EQ(colour.start(loop, [&](const ColourFrame &f) { gotColour.push_back(f); order += 'c'; }, onStatus), 0);
	ASSERT_EQ(depth.start(loop, [&](const DepthFrame &f) { gotDepth.push_back(f); order += 'd'; }, onStatus), 0);
	EventSource guard;
	loop.addTimer(10'000'000, [&] { loop.exit(1); }, guard);
	ASSERT_EQ(loop.run(), 0) << "replay did not reach its end";
	ASSERT_EQ(gotColour.size(), sim.colour.size());
	ASSERT_EQ(gotDepth.size(), sim.depth.size());
	for (size_t i = 0; i < sim.colour.size(); ++i) {
		EXPECT_TRUE(gotColour[i].rgb == sim.colour[i].rgb);
		// mask/ was written beside the frames: each comes with its truth.
		EXPECT_TRUE(gotColour[i].truth == sim.masks[i]) << i;
		// Re-stamped onto this run's clock, the offsets exactly as recorded.
		EXPECT_EQ(gotColour[i].timestampNs - gotColour[0].timestampNs,
			  sim.colour[i].timestampNs - sim.colour[0].timestampNs);
	}
	for (size_t i = 0; i < sim.depth.size(); ++i)
		EXPECT_TRUE(gotDepth[i].depthMm == sim.depth[i].depthMm);
	// Recorded order: a depth frame comes before the colour frames it is paired with.
	std::string expected;
	size_t d = 0;
	for (const ColourFrame &c : sim.colour) {
		while (d < sim.depth.size() && sim.depth[d].timestampNs <= c.timestampNs) {
			expected += 'd';
			d++;
		}
		expected += 'c';
	}
	expected.append(sim.depth.size() - d, 'd');
	EXPECT_EQ(order, expected);
}

TEST(Recording, ReplayOfAMissingFolderIsLostNotFatal)
{
	auto timeline = std::make_shared<ReplayTimeline>(ReplaySettings{ "/nonexistent/rec", true, true });
	ReplayColourCamera colour(timeline);
	EventLoop loop;
	ASSERT_EQ(loop.open(), 0);
	DeviceStatus last;
	ASSERT_EQ(colour.start(loop, [](const ColourFrame &) {}, [&](const DeviceStatus &s) { last = s; }), 0);
	EXPECT_EQ(last.state, DeviceState::Lost);
	EXPECT_NE(last.detail.find("/nonexistent/rec"), std::string::npos);
	EXPECT_EQ(colour.status().state, DeviceState::Lost);
}
