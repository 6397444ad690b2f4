// The V4L2 capture classes without a capture device (hal/v4l2/v4l2_stream.hpp,
// hal/v4l2/v4l2_video_device.hpp): format choice, device names, a node that
// is no capture device refused with its errno and the fd closed again, and
// the stream reporting Lost once and Stopped after stop(). Capture from a
// real device is tested in device_backends_test.cpp and the HIL suite.
#include "hal/event_loop.hpp"
#include "hal/v4l2/query_capabilities_error.hpp"
#include "hal/v4l2/v4l2_stream.hpp"
#include "hal/v4l2/v4l2_video_device.hpp"

#include <gtest/gtest.h>

#include <cerrno>
#include <linux/videodev2.h>
#include <vector>

using namespace depthkey;

TEST(V4l2Stream, ChoosesTheFirstWantedFormatTheDeviceOffers)
{
	const std::vector<uint32_t> wanted = { V4L2_PIX_FMT_YUYV, V4L2_PIX_FMT_MJPEG };
	EXPECT_EQ(chooseFourcc(wanted, { V4L2_PIX_FMT_MJPEG, V4L2_PIX_FMT_YUYV }), V4L2_PIX_FMT_YUYV);
	EXPECT_EQ(chooseFourcc(wanted, { V4L2_PIX_FMT_NV12, V4L2_PIX_FMT_MJPEG }), V4L2_PIX_FMT_MJPEG);
	EXPECT_EQ(chooseFourcc(wanted, { V4L2_PIX_FMT_NV12 }), 0u);
	EXPECT_EQ(chooseFourcc(wanted, {}), 0u);
	EXPECT_EQ(fourccName(V4L2_PIX_FMT_YUYV), "YUYV");
}

TEST(V4l2Stream, BareNamesAreLookedUpByIdAndPathsStay)
{
	EXPECT_EQ(resolveVideoDevice("usb-Logitech_C920-video-index0"),
		  "/dev/v4l/by-id/usb-Logitech_C920-video-index0");
	EXPECT_EQ(resolveVideoDevice("/dev/video0"), "/dev/video0");
}

TEST(V4l2Stream, AnIncompleteConfigIsRefused)
{
	EventLoop loop;
	ASSERT_EQ(loop.open(), 0);
	V4l2StreamConfig config;
	config.device = "/dev/null";
	config.width = 640;
	config.height = 480;
	config.fps = 25;
	V4l2Stream stream;
	auto onBuffer = [](const V4l2Buffer &, const V4l2Format &) { return 0; };
	EXPECT_EQ(stream.start(loop, config, onBuffer, nullptr), -EINVAL); // no format
	config.fourccs = { V4L2_PIX_FMT_YUYV };
	config.fps = 0;
	EXPECT_EQ(stream.start(loop, config, onBuffer, nullptr), -EINVAL);
}

TEST(V4l2Stream, ANodeThatIsNoCaptureDeviceIsLostOnceThenStopped)
{
	EventLoop loop;
	ASSERT_EQ(loop.open(), 0);
	V4l2StreamConfig config;
	config.device = "/dev/null";
	config.fourccs = { V4L2_PIX_FMT_YUYV };
	config.width = 640;
	config.height = 480;
	config.fps = 25;
	int buffers = 0;
	std::vector<DeviceStatus> statuses;
	V4l2Stream stream;
	ASSERT_EQ(stream.start(
			  loop, config,
			  [&](const V4l2Buffer &, const V4l2Format &) {
				  buffers++;
				  return 0;
			  },
			  [&](const DeviceStatus &s) { statuses.push_back(s); }),
		  0);
	EventSource stop;
	loop.addTimer(350'000, [&] { loop.exit(0); }, stop); // several retries (after 100, 200 ms)
	loop.run();
	ASSERT_EQ(statuses.size(), 1u) << "the same failure is reported once";
	EXPECT_EQ(statuses[0].state, DeviceState::Lost);
	EXPECT_EQ(statuses[0].error, -ENOTTY);
	EXPECT_EQ(buffers, 0);
	stream.stop();
	EXPECT_EQ(stream.status().state, DeviceState::Stopped);
}

TEST(V4l2VideoDevice, OpenFailuresAreErrnoAndLeaveNoFd)
{
	V4l2VideoDevice device;
	EXPECT_EQ(device.open("/dev/depthkey-test-no-such-video"), -ENOENT);
	EXPECT_EQ(device.fd(), -1);
	EXPECT_EQ(device.open("/dev/null"), -ENOTTY); // opened, but QUERYCAP fails: closed again
	EXPECT_EQ(device.fd(), -1);
	device.close(); // closing what is closed is harmless
	EXPECT_EQ(device.fd(), -1);
}

TEST(V4l2VideoDevice, QueryCapabilitiesUnemulatedIsNotAV4l2Node)
{
	// qemu-user's ENOSYS for an ioctl it does not emulate reads as a
	// kernel's ENOTTY; every other reason is kept as it is.
	EXPECT_EQ(queryCapabilitiesError(-ENOSYS), -ENOTTY);
	EXPECT_EQ(queryCapabilitiesError(-ENOTTY), -ENOTTY);
	EXPECT_EQ(queryCapabilitiesError(-EBUSY), -EBUSY);
	EXPECT_EQ(queryCapabilitiesError(-ENODEV), -ENODEV);
	EXPECT_EQ(queryCapabilitiesError(0), 0);
}
