// The virtual webcam's writer (hal/v4l2/v4l2_output.hpp) on a fake device: a
// FIFO stands where the v4l2loopback node would be (a reader that stops
// reading fills it: the writer must drop, not wait; a reader that goes away
// makes write() fail with EPIPE: the writer must close and re-open with the
// cameras' backoff). The real backend is refused on nodes that are no video
// output. Writing to a real v4l2loopback device is in the HIL suite.
#include "allocation_counter.hpp"
#include "hal/event_loop.hpp"
#include "hal/v4l2/rgb_to_yuyv.hpp"
#include "hal/v4l2/v4l2_output.hpp"

#include <gtest/gtest.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <cstdlib>
#include <fcntl.h>
#include <string>
#include <sys/stat.h>
#include <unistd.h>
#include <vector>

using namespace depthkey;

namespace {

// A FIFO as the device: no format to set; opening it without a reader fails
// with ENXIO, as opening a vanished node fails.
class FifoOutputDevice : public VideoOutputDevice
{
public:
	explicit FifoOutputDevice(int *opens) : opens_(opens) {}
	~FifoOutputDevice() override { close(); }
	int open(const std::string &path, int, int, size_t, std::string &detail) override
	{
		(*opens_)++;
		fd_ = ::open(path.c_str(), O_WRONLY | O_NONBLOCK | O_CLOEXEC);
		if (fd_ < 0) {
			detail = path + ": open: " + std::strerror(errno);
			return -errno;
		}
		return 0;
	}
	ssize_t write(const uint8_t *data, size_t bytes) override
	{
		ssize_t n = ::write(fd_, data, bytes);
		return n < 0 ? -errno : n;
	}
	void close() override
	{
		if (fd_ >= 0)
			::close(fd_);
		fd_ = -1;
	}

private:
	int *opens_;
	int fd_ = -1;
};

struct Fifo {
	std::string path;
	Fifo()
	{
		char dir[] = "/tmp/depthkey-vcam-XXXXXX";
		path = std::string(mkdtemp(dir)) + "/video10";
		mkfifo(path.c_str(), 0600);
	}
	~Fifo()
	{
		unlink(path.c_str());
		rmdir(path.substr(0, path.rfind('/')).c_str());
	}
	// A reader end, non-blocking.
	int openReader() const { return ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC); }
};

RgbImage testImage(int width, int height, uint8_t shade)
{
	RgbImage image(width, height);
	for (int y = 0; y < height; y++)
		for (int x = 0; x < width; x++)
			image.at(x, y) = { static_cast<uint8_t>(shade + x), static_cast<uint8_t>(y * 3), shade };
	return image;
}

void runFor(EventLoop &loop, uint64_t ms)
{
	EventSource stop;
	loop.addTimer(ms * 1000, [&] { loop.exit(0); }, stop);
	loop.run();
}

class V4l2OutputTest : public ::testing::Test
{
protected:
	void SetUp() override
	{
		std::signal(SIGPIPE, SIG_IGN); // the FIFO's reader going away
		ASSERT_EQ(loop.open(), 0);
	}
	void start()
	{
		output.start(loop, fifo.path, [this](const DeviceStatus &s) { changes.push_back(s); });
	}

	EventLoop loop;
	Fifo fifo;
	int opens = 0;
	V4l2Output output{ std::make_unique<FifoOutputDevice>(&opens) };
	std::vector<DeviceStatus> changes;
};

} // namespace

TEST_F(V4l2OutputTest, OffWritesNothingAndOpensNothing)
{
	output.start(loop, "", nullptr);
	EXPECT_FALSE(output.enabled());
	EXPECT_EQ(output.write(testImage(16, 8, 10)), -ENODEV);
	EXPECT_EQ(opens, 0);
	EXPECT_STREQ(v4l2OutputStateName(output.status().state), "off");
}

TEST_F(V4l2OutputTest, WritesEachFrameAsYuyvAtTheImagesSize)
{
	int reader = fifo.openReader();
	ASSERT_GE(reader, 0);
	start();
	EXPECT_EQ(opens, 0) << "the size comes with the first frame";
	RgbImage image = testImage(17, 6, 40); // odd width: 18 columns of YUYV
	ASSERT_EQ(output.write(image), 0);
	ASSERT_EQ(output.write(image), 0);
	std::vector<uint8_t> want(yuyvFrameBytes(17, 6));
	ASSERT_EQ(rgbToYuyv(image, want.data(), want.size()), 0);
	std::vector<uint8_t> got(want.size() * 2);
	ASSERT_EQ(read(reader, got.data(), got.size()), static_cast<ssize_t>(got.size()));
	EXPECT_TRUE(std::equal(want.begin(), want.end(), got.begin()));
	EXPECT_TRUE(std::equal(want.begin(), want.end(), got.begin() + static_cast<long>(want.size())));
	EXPECT_EQ(output.framesWritten(), 2u);
	EXPECT_EQ(opens, 1);
	ASSERT_EQ(changes.size(), 1u);
	EXPECT_EQ(changes[0].state, DeviceState::Streaming);
	EXPECT_STREQ(v4l2OutputStateName(output.status().state), "writing");
	close(reader);
}

TEST_F(V4l2OutputTest, AFullDeviceDropsFramesWithoutWaitingAndWithoutAllocating)
{
	int reader = fifo.openReader(); // never read
	ASSERT_GE(reader, 0);
	fcntl(reader, F_SETPIPE_SZ, 4096);
	start();
	RgbImage image = testImage(32, 24, 20); // 1.5 KiB of YUYV: two frames fit, not three
	ASSERT_EQ(output.write(image), 0);
	ASSERT_EQ(output.write(image), 0);
	const auto begin = std::chrono::steady_clock::now();
	int dropped = 0;
	{
		test::CountAllocations allocations;
		for (int i = 0; i < 50; i++)
			dropped += output.write(image) == -EAGAIN;
		if (test::allocationCounting()) {
			EXPECT_EQ(allocations.count(), 0u) << "nothing allocated per frame";
		}
	}
	const auto took = std::chrono::steady_clock::now() - begin;
	EXPECT_EQ(dropped, 50);
	EXPECT_EQ(output.status().droppedFrames, 50u);
	EXPECT_LT(took, std::chrono::milliseconds(200)) << "50 writes must not wait for the reader";
	EXPECT_EQ(output.status().state, DeviceState::Streaming) << "a full device is not a lost one";
	EXPECT_EQ(changes.size(), 1u);
	close(reader);
}

TEST_F(V4l2OutputTest, AVanishedDeviceIsLostOnceAndReopenedWithBackoff)
{
	int reader = fifo.openReader();
	ASSERT_GE(reader, 0);
	start();
	RgbImage image = testImage(16, 8, 30);
	ASSERT_EQ(output.write(image), 0);
	close(reader); // the device goes away: EPIPE
	EXPECT_EQ(output.write(image), -EPIPE);
	ASSERT_EQ(changes.size(), 2u);
	EXPECT_EQ(changes[1].state, DeviceState::Lost);
	EXPECT_EQ(changes[1].error, -EPIPE);
	EXPECT_EQ(output.write(image), -ENODEV) << "nothing written while lost";

	// Nobody there for 1 s: retries at 0.1, 0.3, 0.7 s... each open fails with
	// ENXIO; the journal hears of the change of error once, not per attempt.
	// Then the device is back: the next retry (at most 0.5 s on) opens it.
	// (One run of the loop: an sd-event loop that exited does not run again.)
	const int opensBefore = opens;
	int opensWhileAway = 0;
	size_t changesWhileAway = 0;
	EventSource back;
	loop.addTimer(1'000'000, [&] {
		opensWhileAway = opens - opensBefore;
		changesWhileAway = changes.size();
		reader = fifo.openReader();
	}, back);
	runFor(loop, 1600);
	EXPECT_GE(opensWhileAway, 3);
	EXPECT_LE(opensWhileAway, 5) << "backoff: 100, 200, 400, 500 ms";
	EXPECT_EQ(changesWhileAway, 3u);
	EXPECT_EQ(changes[2].error, -ENXIO);
	ASSERT_GE(reader, 0);
	EXPECT_EQ(output.write(image), 0) << opens << " opens, " << changes.back().detail;
	ASSERT_EQ(changes.size(), 4u);
	EXPECT_EQ(changes[3].state, DeviceState::Streaming);
	uint8_t buffer[512];
	EXPECT_EQ(read(reader, buffer, sizeof(buffer)), static_cast<ssize_t>(yuyvFrameBytes(16, 8)));
	close(reader);
}

TEST_F(V4l2OutputTest, ANewSizeReopensTheDevice)
{
	int reader = fifo.openReader();
	ASSERT_GE(reader, 0);
	start();
	ASSERT_EQ(output.write(testImage(16, 8, 1)), 0);
	ASSERT_EQ(output.write(testImage(32, 8, 1)), 0);
	EXPECT_EQ(opens, 2);
	close(reader);
}

TEST(V4l2OutputDevice, ANodeThatIsNoVideoOutputIsRefusedWithTheReason)
{
	V4l2OutputDevice device;
	std::string detail;
	EXPECT_EQ(device.open("/dev/null", 640, 480, 640 * 480 * 2, detail), -ENOTTY);
	EXPECT_NE(detail.find("/dev/null: not a V4L2 device"), std::string::npos) << detail;
	EXPECT_EQ(device.open("/nonexistent/video10", 640, 480, 640 * 480 * 2, detail), -ENOENT);
	EXPECT_NE(detail.find("open"), std::string::npos) << detail;
	uint8_t byte = 0;
	EXPECT_EQ(device.write(&byte, 1), -EBADF);
}

TEST(V4l2OutputDevice, TheRealBackendOnAMissingNodeIsLostAndRetried)
{
	EventLoop loop;
	ASSERT_EQ(loop.open(), 0);
	V4l2Output output;
	std::vector<DeviceStatus> changes;
	output.start(loop, "/nonexistent/video10", [&](const DeviceStatus &s) { changes.push_back(s); });
	EXPECT_EQ(output.write(testImage(16, 8, 0)), -ENODEV);
	ASSERT_EQ(changes.size(), 1u);
	EXPECT_EQ(changes[0].state, DeviceState::Lost);
	EXPECT_EQ(changes[0].error, -ENOENT);
	output.stop();
	EXPECT_EQ(output.status().state, DeviceState::Stopped);
}
