// The real backends on this machine: without devices they must report Lost
// with the reason and keep the loop running; with a device present frames
// must flow. Tests that need a device this machine lacks are skipped.
#include <gtest/gtest.h>

#include "hal/gpio/gpiod_status_leds.hpp"
#include "hal/sr2/sr2_camera.hpp"
#include "hal/sr2/sr2_protocol.hpp"
#include "hal/v4l2/v4l2_cameras.hpp"

#include <cerrno>
#include <filesystem>
#include <libusb.h>

using namespace depthkey;

namespace {

// Runs the loop for ms milliseconds.
void runFor(EventLoop &loop, uint64_t ms)
{
	EventSource stop;
	loop.addTimer(ms * 1000, [&] { loop.exit(0); }, stop);
	loop.run();
}

std::string firstVideoDevice()
{
	std::error_code ec;
	for (const auto &entry : std::filesystem::directory_iterator("/dev", ec))
		if (entry.path().filename().string().rfind("video", 0) == 0)
			return entry.path().string();
	return "";
}

bool sr2Present()
{
	libusb_context *ctx = nullptr;
	if (libusb_init(&ctx) < 0)
		return false;
	libusb_device_handle *h = libusb_open_device_with_vid_pid(ctx, sr2::kVendorId, sr2::kProductId);
	bool found = h != nullptr;
	if (h)
		libusb_close(h);
	libusb_exit(ctx);
	return found;
}

template<typename Frame>
struct Recorder {
	std::vector<DeviceStatus> statuses;
	int frames = 0;
	typename Camera<Frame>::FrameHandler onFrame() { return [this](const Frame &) { frames++; }; }
	typename Camera<Frame>::StatusHandler onStatus()
	{
		return [this](const DeviceStatus &s) { statuses.push_back(s); };
	}
};

// Streams for 2 s from a device that is there: it must stream and deliver.
template<typename Frame>
void expectFramesFlow(Camera<Frame> &camera, int minFrames)
{
	EventLoop loop;
	ASSERT_EQ(loop.open(), 0);
	Recorder<Frame> rec;
	ASSERT_EQ(camera.start(loop, rec.onFrame(), rec.onStatus()), 0);
	runFor(loop, 2000);
	EXPECT_EQ(camera.status().state, DeviceState::Streaming) << camera.status().detail;
	EXPECT_GT(rec.frames, minFrames);
	camera.stop();
}

} // namespace

TEST(V4l2Backend, MissingDeviceIsLostWithTheReasonAndRetried)
{
	EventLoop loop;
	ASSERT_EQ(loop.open(), 0);
	ColourCameraSettings settings;
	settings.backend = "v4l2";
	settings.device = "usb-depthkey-test-no-such-camera";
	V4l2ColourCamera camera(settings);
	Recorder<ColourFrame> rec;
	ASSERT_EQ(camera.start(loop, rec.onFrame(), rec.onStatus()), 0);
	runFor(loop, 400); // several retries (100, 200 ms)
	ASSERT_EQ(rec.statuses.size(), 1u) << "the same failure is reported once";
	EXPECT_EQ(rec.statuses[0].state, DeviceState::Lost);
	EXPECT_EQ(rec.statuses[0].error, -ENOENT);
	EXPECT_NE(rec.statuses[0].detail.find("/dev/v4l/by-id/usb-depthkey-test-no-such-camera"),
		  std::string::npos) << rec.statuses[0].detail;
	camera.stop();
	EXPECT_EQ(camera.status().state, DeviceState::Stopped);
}

TEST(V4l2Backend, ANodeThatIsNoCaptureDeviceIsRefused)
{
	EventLoop loop;
	ASSERT_EQ(loop.open(), 0);
	DepthCameraSettings settings;
	settings.device = "/dev/null";
	V4l2DepthCamera camera(settings);
	Recorder<DepthFrame> rec;
	ASSERT_EQ(camera.start(loop, rec.onFrame(), rec.onStatus()), 0);
	runFor(loop, 50);
	EXPECT_EQ(camera.status().state, DeviceState::Lost);
	EXPECT_EQ(camera.status().error, -ENOTTY);
	EXPECT_EQ(rec.frames, 0);
}

TEST(V4l2Backend, CapturesFromARealDevice)
{
	std::string device = firstVideoDevice();
	if (device.empty())
		GTEST_SKIP() << "no /dev/video* on this machine (the HIL VM runs this against vivid)";
	ColourCameraSettings settings;
	settings.device = device;
	V4l2ColourCamera camera(settings);
	expectFramesFlow(camera, 10);
}

TEST(Sr2Backend, MissingCameraIsLostAndTheLoopRunsOn)
{
	if (sr2Present())
		GTEST_SKIP() << "an SR-2 is plugged in";
	EventLoop loop;
	ASSERT_EQ(loop.open(), 0);
	DepthCameraSettings settings;
	settings.backend = "sr2";
	Sr2Camera camera(settings);
	Recorder<DepthFrame> rec;
	int ret = camera.start(loop, rec.onFrame(), rec.onStatus());
	if (ret < 0)
		GTEST_SKIP() << "libusb cannot initialise here: " << ret;
	int ticks = 0;
	EventSource tick;
	loop.addPeriodic(10'000, [&] { ticks++; }, tick);
	runFor(loop, 400);
	EXPECT_GT(ticks, 20) << "the loop is never blocked by the camera";
	ASSERT_EQ(rec.statuses.size(), 1u);
	EXPECT_EQ(rec.statuses[0].state, DeviceState::Lost);
	EXPECT_EQ(rec.statuses[0].error, -ENODEV);
	EXPECT_EQ(rec.statuses[0].detail, "no SR-2 (0852:0071)");
	camera.stop();
	EXPECT_EQ(camera.status().state, DeviceState::Stopped);
}

TEST(Sr2Backend, StreamsFromARealCamera)
{
	if (!sr2Present())
		GTEST_SKIP() << "no SR-2 (0852:0071) on USB (the HIL VM runs this against the emulated SR-2)";
	Sr2Camera camera(DepthCameraSettings{});
	expectFramesFlow(camera, 5);
}

TEST(GpiodLeds, MissingChipIsReportedOnceAndFailsSoftly)
{
	EventLoop loop;
	ASSERT_EQ(loop.open(), 0);
	std::vector<std::string> faults;
	GpiodStatusLeds leds([&](const std::string &led, int error, const std::string &detail) {
		faults.push_back(led + "|" + std::to_string(error) + "|" + detail);
	});
	LedSettings settings;
	settings.chip = "depthkey-test-no-such-chip";
	EXPECT_LT(leds.open(loop, settings), 0);
	ASSERT_EQ(faults.size(), 1u);
	EXPECT_EQ(faults[0].rfind("|-2|cannot open GPIO chip depthkey-test-no-such-chip", 0), 0u)
		<< faults[0];
	EXPECT_EQ(leds.linesInUse(), 0);
	leds.show(StatusSummary{}); // harmless without lines
	runFor(loop, 300);
	leds.close();
	EXPECT_EQ(faults.size(), 1u);
}
