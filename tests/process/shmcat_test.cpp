// depthkey-shmcat end to end: frames written with ShmRingWriter, dumped as
// YUV4MPEG2, decoded back to RGB(A) by ffmpeg and compared with what was
// written.
#include "hal/depthkey_shm.h"
#include "hal/shm_ring_writer.hpp"
#include "tests/process/piped_command.hpp"
#include "tests/shm_test_util.hpp"
#include "tests/test_paths.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <sys/wait.h>
#include <thread>
#include <vector>

using namespace depthkey;
using depthkey::test::ShmName;
using depthkey::test::Result;
using depthkey::test::runPiped;

namespace {

constexpr int kWidth = 48, kHeight = 32;

// Our integer BT.601 full-range conversion, 8-bit y4m and ffmpeg's own
// conversion back to RGB each round once: the worst error measured with
// ffmpeg 5.1 is 1 level per channel; 3 leaves room for other swscale
// versions, while a range or matrix mix-up (limited vs full, BT.709) would
// be off by 10 or more. Alpha is copied: exact.
constexpr int kColourTolerance = 3;

std::string shmcat()
{
	return depthkey::test::binDir() + "/depthkey-shmcat";
}

// Saturated primaries, greys, skin-like tones and gradients; with alpha for
// the lecturer stream.
std::vector<uint8_t> testImage(int bpp)
{
	static const uint8_t patches[][3] = {
		{ 255, 0, 0 }, { 0, 255, 0 }, { 0, 0, 255 }, { 255, 255, 255 },
		{ 0, 0, 0 }, { 128, 128, 128 }, { 224, 172, 140 }, { 30, 60, 40 },
	};
	std::vector<uint8_t> image(static_cast<size_t>(kWidth) * kHeight * bpp);
	for (int y = 0; y < kHeight; y++) {
		for (int x = 0; x < kWidth; x++) {
			uint8_t *p = &image[(static_cast<size_t>(y) * kWidth + x) * bpp];
			if (y < kHeight / 2) {
				const uint8_t *c = patches[x / (kWidth / 8)];
				p[0] = c[0], p[1] = c[1], p[2] = c[2];
			} else {
				p[0] = static_cast<uint8_t>(x * 255 / (kWidth - 1));
				p[1] = static_cast<uint8_t>(y * 8);
				p[2] = static_cast<uint8_t>(255 - x * 5);
			}
			if (bpp == 4)
				p[3] = static_cast<uint8_t>((x * 37 + y * 11) % 256);
		}
	}
	return image;
}

// Writes the same image every 4 ms until stopped; optionally restarts the
// writer (new generation, frame numbers from 1 again) after some frames.
class Feeder
{
public:
	Feeder(ShmRingWriter &writer, const std::vector<uint8_t> &image, int restartAfter = 0,
	       int firstFrame = 1)
		: thread_([this, &writer, &image, restartAfter, firstFrame] {
			  for (int f = firstFrame; !stop_; f++) {
				  if (restartAfter && f % restartAfter == 0)
					  writer.open(writer.name(), writer.width(), writer.height(),
						      writer.fourcc(), writer.slots(), "");
				  writer.write(image.data(), writer.stride(), f * 4000000ull,
					       DK_SHM_FLAG_ONLINE);
				  std::this_thread::sleep_for(std::chrono::milliseconds(4));
			  }
		  })
	{
	}
	~Feeder()
	{
		stop_ = true;
		thread_.join();
	}

private:
	std::atomic<bool> stop_{ false };
	std::thread thread_;
};

// Decoded frames must match the written image within kColourTolerance (and
// exactly for alpha); reports the worst error seen.
void expectFrames(const Result &r, int frames, const std::vector<uint8_t> &image, int bpp)
{
	ASSERT_EQ(r.status, 0) << r.err;
	ASSERT_EQ(r.out.size(), image.size() * frames) << r.err;
	int worst = 0, worstAlpha = 0;
	for (size_t i = 0; i < r.out.size(); i++) {
		int diff = std::abs(static_cast<uint8_t>(r.out[i]) - image[i % image.size()]);
		int &slot = (bpp == 4 && i % 4 == 3) ? worstAlpha : worst;
		slot = std::max(slot, diff);
	}
	std::printf("    worst colour error %d, alpha error %d\n", worst, worstAlpha);
	EXPECT_LE(worst, kColourTolerance);
	EXPECT_EQ(worstAlpha, 0);
}

class ShmCatTest : public testing::Test
{
protected:
	void SetUp() override
	{
		if (access(shmcat().c_str(), X_OK) != 0)
			FAIL() << shmcat() << " is missing: make all";
		if (system("command -v ffmpeg >/dev/null 2>&1") != 0)
			GTEST_SKIP() << "ffmpeg is not installed";
	}
};

} // namespace

TEST_F(ShmCatTest, CompositeDecodesToTheWrittenColours)
{
	ShmName name;
	ShmRingWriter writer;
	ASSERT_EQ(writer.open(name.str(), kWidth, kHeight, DK_SHM_FORMAT_RGB24, 3, ""), 0);
	const auto image = testImage(3);
	Feeder feeder(writer, image);
	Result r = runPiped(shmcat() + " --name " + name.str() + " --frames 12 | ffmpeg -v error "
		       "-f yuv4mpegpipe -i - -f rawvideo -pix_fmt rgb24 -");
	expectFrames(r, 12, image, 3);
}

TEST_F(ShmCatTest, LecturerKeepsStraightAlpha)
{
	ShmName name;
	ShmRingWriter writer;
	ASSERT_EQ(writer.open(name.str(), kWidth, kHeight, DK_SHM_FORMAT_RGBA32, 3, ""), 0);
	const auto image = testImage(4);
	Feeder feeder(writer, image);
	Result header = runPiped(shmcat() + " --name " + name.str() + " --frames 1 | head -c 100");
	EXPECT_NE(header.out.find("C444alpha"), std::string::npos) << header.out;
	Result r = runPiped(shmcat() + " --stream lecturer --name " + name.str() + " --frames 8 | "
		       "ffmpeg -v error -f yuv4mpegpipe -i - -f rawvideo -pix_fmt rgba -");
	expectFrames(r, 8, image, 4);
}

// Probing must recognise the stream: "depthkey-shmcat | ffmpeg -i - out.mp4".
TEST_F(ShmCatTest, FfmpegProbesTheStream)
{
	ShmName name;
	ShmRingWriter writer;
	ASSERT_EQ(writer.open(name.str(), kWidth, kHeight, DK_SHM_FORMAT_RGB24, 3, ""), 0);
	const auto image = testImage(3);
	Feeder feeder(writer, image);
	Result r = runPiped(shmcat() + " --name " + name.str() + " --frames 5 --fps 30 | "
		       "ffmpeg -v error -i - -f rawvideo -pix_fmt rgb24 -");
	expectFrames(r, 5, image, 3);
}

// The first frame read may be captured well after the stream's capture
// clock started (here 2 s, as a reader slowed by a sanitizer saw it): no
// frame is written for the slots before it, as there is none to repeat.
// (Under ASan FfmpegProbesTheStream got 5 blank frames this way.)
TEST_F(ShmCatTest, AFirstFrameLateInTheCaptureClockComesFirst)
{
	ShmName name;
	ShmRingWriter writer;
	ASSERT_EQ(writer.open(name.str(), kWidth, kHeight, DK_SHM_FORMAT_RGB24, 3, ""), 0);
	const auto image = testImage(3);
	Feeder feeder(writer, image, 0, 500); // capture times from 2 s
	Result r = runPiped(shmcat() + " --name " + name.str() + " --frames 5 --fps 30 | "
		       "ffmpeg -v error -f yuv4mpegpipe -i - -f rawvideo -pix_fmt rgb24 -");
	expectFrames(r, 5, image, 3);
}

TEST_F(ShmCatTest, FollowsAWriterRestart)
{
	ShmName name;
	ShmRingWriter writer;
	ASSERT_EQ(writer.open(name.str(), kWidth, kHeight, DK_SHM_FORMAT_RGB24, 3, ""), 0);
	const auto image = testImage(3);
	Feeder feeder(writer, image, 5); // a new generation every 5 frames
	Result r = runPiped(shmcat() + " --name " + name.str() + " --frames 16 | ffmpeg -v error "
		       "-f yuv4mpegpipe -i - -f rawvideo -pix_fmt rgb24 -");
	expectFrames(r, 16, image, 3);
}

TEST_F(ShmCatTest, TimeoutWithoutNewFrames)
{
	ShmName name;
	ShmRingWriter writer;
	ASSERT_EQ(writer.open(name.str(), kWidth, kHeight, DK_SHM_FORMAT_RGB24, 3, ""), 0);
	const auto image = testImage(3);
	ASSERT_EQ(writer.write(image.data(), writer.stride(), 1, 0), 0);
	writer.close(); // offline: the last frame stays, no new ones come
	Result r = runPiped(shmcat() + " --name " + name.str() + " --frames 3 --timeout 0.3");
	EXPECT_NE(r.status, 0);
	EXPECT_NE(r.err.find("timeout"), std::string::npos) << r.err;
	EXPECT_NE(r.err.find(name.str()), std::string::npos) << r.err;
	EXPECT_NE(r.err.find("offline"), std::string::npos) << r.err;
	// The one frame there was has been emitted, after the header.
	const size_t header = r.out.find('\n') + 1;
	EXPECT_EQ(r.out.size(), header + 6 + image.size());
}

TEST_F(ShmCatTest, MissingObjectFailsAtOnce)
{
	ShmName name;
	auto start = std::chrono::steady_clock::now();
	Result r = runPiped(shmcat() + " --name " + name.str() + " --timeout 10");
	EXPECT_NE(r.status, 0);
	EXPECT_NE(r.err.find(name.str() + " does not exist"), std::string::npos) << r.err;
	EXPECT_TRUE(r.out.empty());
	EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));
}

TEST_F(ShmCatTest, BadOptionsAreUsageErrors)
{
	EXPECT_EQ(runPiped(shmcat() + " --frames many").status, 2);
	EXPECT_EQ(runPiped(shmcat() + " --stream depth").status, 2);
	EXPECT_EQ(runPiped(shmcat() + " --timeout 0").status, 2);
}
