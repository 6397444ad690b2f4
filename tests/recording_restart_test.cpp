// Issue 31: a restart must not overwrite a recording. The daemon's recorder
// is started three times on one record_dir (as three daemon runs would), and
// in the last run the cameras restart too (a reload or a re-open): each run's
// camera sequences start at 1 again. Every frame must be on disk once, under
// its own name, the index must list each name once in time order, and the
// folder must read back as one sequence with the frames that were recorded.
#include "daemon/frame_recorder.hpp"
#include "hal/recording/sequence_reader.hpp"
#include "tests/wait_until.hpp"

#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <set>
#include <sstream>
#include <tuple>

using namespace depthkey;
using namespace std::chrono_literals;

namespace {

constexpr int kFramesPerRun = 12;

// A colour frame whose pixels say which it is, so a read-back shows whether
// its file was overwritten by another frame.
ColourFrame colourFrame(uint8_t id, uint64_t sequence, uint64_t timestampNs, int width = 8, int height = 6)
{
	ColourFrame f;
	f.rgb = RgbImage(width, height, { id, uint8_t(id ^ 0x5a), 7 });
	f.sequence = sequence;
	f.timestampNs = timestampNs;
	return f;
}

DepthFrame depthFrame(uint16_t id, uint64_t sequence, uint64_t timestampNs)
{
	DepthFrame f;
	f.depthMm = Gray16Image(4, 3, uint16_t(1000 + id));
	f.amplitude = Gray16Image(4, 3, id);
	f.sequence = sequence;
	f.timestampNs = timestampNs;
	return f;
}

// Records one frame pair and waits for both to be written, so that none is
// dropped by a worker a loaded machine holds up.
void recordPair(FrameRecorder &recorder, uint8_t id, uint64_t sequence, uint64_t timestampNs, int width = 8,
		int height = 6)
{
	const uint64_t before = recorder.written();
	recorder.recordColour(colourFrame(id, sequence, timestampNs, width, height));
	recorder.recordDepth(depthFrame(id, sequence, timestampNs));
	ASSERT_TRUE(depthkey::test::waitUntil([&] { return recorder.written() >= before + 2; }, 10s));
}

// The file names an index lists, in its order.
std::vector<std::string> indexNames(const std::string &path)
{
	std::ifstream in(path);
	std::vector<std::string> names;
	for (std::string line; std::getline(in, line);) {
		if (line.empty() || line[0] == '#')
			continue;
		std::istringstream fields(line);
		std::string stamp, name;
		fields >> stamp >> name;
		names.push_back(name);
	}
	return names;
}

} // namespace

TEST(RecordingRestart, ThreeRestartsKeepEveryFrameOnce)
{
	const std::filesystem::path dir =
		std::filesystem::temp_directory_path() / ("depthkey-restart-" + std::to_string(getpid()));
	std::filesystem::remove_all(dir);

	uint8_t id = 0;
	uint64_t timestampNs = 1'000'000'000;
	for (int run = 0; run < 3; run++) {
		FrameRecorder recorder;
		std::string error;
		ASSERT_EQ(recorder.start(dir.string(), 0, error), 0) << error;
		for (int i = 1; i <= kFramesPerRun; i++) {
			// The last run's cameras restart half-way: sequences from 1 again.
			const uint64_t sequence = run == 2 && i > kFramesPerRun / 2 ? i - kFramesPerRun / 2 : i;
			// A dropped frame in the middle of each run stays a gap.
			if (i == 3)
				continue;
			recordPair(recorder, ++id, sequence, timestampNs += 40'000'000);
		}
		recorder.stop();
		EXPECT_EQ(recorder.takeError(), "");
	}
	const size_t frames = id;

	for (const char *stream : { "rgb", "depth", "amplitude" }) {
		const std::vector<std::string> names = indexNames((dir / (std::string(stream) + ".txt")).string());
		EXPECT_EQ(names.size(), frames) << stream;
		EXPECT_EQ(std::set<std::string>(names.begin(), names.end()).size(), names.size())
			<< stream << ": a name is listed twice";
		size_t files = 0;
		for (const auto &entry : std::filesystem::directory_iterator(dir / stream))
			files += entry.path().extension() == ".png";
		EXPECT_EQ(files, frames) << stream << ": files overwritten or left over";
	}

	// One sequence, read back frame for frame: each file holds its own frame.
	SequenceReader reader;
	ASSERT_EQ(reader.open(dir.string(), { recording::Rgb, recording::Depth, recording::Amplitude }), 0)
		<< reader.describeError();
	ASSERT_EQ(reader.colour().size(), frames);
	ASSERT_EQ(reader.depth().size(), frames);
	uint64_t previousSequence = 0;
	for (size_t i = 0; i < frames; i++) {
		ColourFrame colour;
		DepthFrame depth;
		ASSERT_EQ(reader.readColour(i, colour), 0) << reader.describeError();
		ASSERT_EQ(reader.readDepth(i, depth), 0) << reader.describeError();
		EXPECT_EQ(colour.rgb.at(0, 0).r, uint8_t(i + 1)) << "frame " << i;
		EXPECT_EQ(depth.depthMm.at(0, 0), uint16_t(1000 + i + 1)) << "frame " << i;
		EXPECT_EQ(depth.amplitude.at(0, 0), uint16_t(i + 1)) << "frame " << i;
		EXPECT_EQ(colour.sequence, depth.sequence) << "frame " << i;
		EXPECT_GT(colour.sequence, previousSequence) << "frame " << i;
		previousSequence = colour.sequence;
	}
	std::filesystem::remove_all(dir);
}

// After a reboot CLOCK_MONOTONIC starts again: a folder whose frames are
// stamped later than now was recorded in an earlier boot. Appending would
// make its index go back in time, which the reader refuses; the session
// goes into DIR/boot-2 instead, and the next run of the same boot appends
// there. Both folders read back whole.
TEST(RecordingRestart, AFolderOfAnEarlierBootIsKeptAndTheSessionGoesBeside)
{
	const std::filesystem::path dir =
		std::filesystem::temp_directory_path() / ("depthkey-reboot-" + std::to_string(getpid()));
	std::filesystem::remove_all(dir);
	timespec now{};
	clock_gettime(CLOCK_MONOTONIC, &now);
	const uint64_t nowNs = static_cast<uint64_t>(now.tv_sec) * 1000000000u + static_cast<uint64_t>(now.tv_nsec);
	const uint64_t earlierBootNs = nowNs + 86'400'000'000'000u; // a day of uptime before the reboot

	uint8_t id = 0;
	for (int run = 0; run < 3; run++) {
		FrameRecorder recorder;
		std::string error;
		ASSERT_EQ(recorder.start(dir.string(), 0, error), 0) << error;
		EXPECT_EQ(recorder.dir(), run == 0 ? dir.string() : (dir / "boot-2").string()) << run;
		for (int i = 1; i <= 4; i++)
			recordPair(recorder, ++id, i, (run == 0 ? earlierBootNs : nowNs - 10'000'000'000u) + (run * 4 + i) * 40'000'000u);
		recorder.stop();
	}
	for (const auto &[folder, frames] : { std::pair{ dir, 4u }, std::pair{ dir / "boot-2", 8u } }) {
		SequenceReader reader;
		ASSERT_EQ(reader.open(folder.string()), 0) << reader.describeError();
		EXPECT_EQ(reader.colour().size(), frames) << folder;
		EXPECT_EQ(reader.depth().size(), frames) << folder;
	}
	EXPECT_FALSE(std::filesystem::exists(dir / "boot-3"));
	std::filesystem::remove_all(dir);
}

// Issue 31 point 14: a reload that changed [colour]'s size appended frames of
// the new size to the folder, and a replay at either size refused half of it.
// A session of another colour size goes into DIR/WxH; back at the first
// size, the folder is appended to again. Each folder holds one size.
TEST(RecordingRestart, AnotherColourSizeGoesIntoAFolderOfItsOwn)
{
	const std::filesystem::path dir =
		std::filesystem::temp_directory_path() / ("depthkey-resize-" + std::to_string(getpid()));
	std::filesystem::remove_all(dir);
	const std::filesystem::path resized = dir / "16x12";
	const struct {
		int width, height;
		std::filesystem::path folder;
	} runs[] = { { 8, 6, dir }, { 16, 12, resized }, { 8, 6, dir } };

	uint8_t id = 0;
	uint64_t timestampNs = 1'000'000'000;
	for (const auto &run : runs) {
		FrameRecorder recorder;
		std::string error;
		ASSERT_EQ(recorder.start(dir.string(), 0, error, run.width, run.height), 0) << error;
		EXPECT_EQ(recorder.dir(), run.folder.string());
		for (int i = 1; i <= 3; i++)
			recordPair(recorder, ++id, i, timestampNs += 40'000'000, run.width, run.height);
		recorder.stop();
	}
	for (const auto &[folder, width, frames] : { std::tuple{ dir, 8, 6u }, std::tuple{ resized, 16, 3u } }) {
		SequenceReader reader;
		ASSERT_EQ(reader.open(folder.string()), 0) << reader.describeError();
		ASSERT_EQ(reader.colour().size(), frames) << folder;
		for (size_t i = 0; i < frames; i++) {
			ColourFrame colour;
			ASSERT_EQ(reader.readColour(i, colour), 0) << reader.describeError();
			EXPECT_EQ(colour.rgb.width(), width) << folder << " frame " << i;
		}
	}
	std::filesystem::remove_all(dir);
}
