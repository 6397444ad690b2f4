// The device keys of the config: every refusal names the key and its place.
#include <gtest/gtest.h>

#include "config/config_loader.hpp"

using namespace depthkey;

namespace {

std::vector<std::string> errorsOf(std::string_view text)
{
	std::vector<std::string> out;
	for (const ConfigError &e : parseConfig(text, "t.toml").errors)
		out.push_back(e.toString());
	return out;
}

using Errors = std::vector<std::string>;

} // namespace

TEST(DeviceConfig, UsbPathMustBeAPortPath)
{
	EXPECT_EQ(errorsOf("[depth]\nusb_path = \"1-2.3\"\n"), Errors{});
	EXPECT_EQ(errorsOf("[depth]\nusb_path = \"3-1\"\n"), Errors{});
	for (const char *bad : { "usb1", "1-", "-2", "1-2..3", "1-2.", "1-a" })
		EXPECT_EQ(errorsOf(std::string("[depth]\nusb_path = \"") + bad + "\"\n").size(), 1u)
			<< bad;
	EXPECT_EQ(errorsOf("[depth]\nusb_path = \"1-2.\"\n"),
		  Errors{ "t.toml:2:12: depth.usb_path: \"1-2.\" must be \"\" or a USB port path "
			  "BUS-PORT[.PORT...], e.g. \"1-2.3\"" });
}

TEST(DeviceConfig, VideoDeviceIsAPathOrAByIdName)
{
	EXPECT_EQ(errorsOf("[colour]\ndevice = \"usb-Cam_123-video-index0\"\n"), Errors{});
	EXPECT_EQ(errorsOf("[colour]\ndevice = \"v4l/by-id/cam\"\n"),
		  Errors{ "t.toml:2:10: colour.device: \"v4l/by-id/cam\" must be an absolute path "
			  "or a name in /dev/v4l/by-id/" });
}

TEST(DeviceConfig, Sr2RegisterWritesNeedAddressAndValueInRange)
{
	ConfigResult ok = parseConfig("[[depth.sr2_register]]\naddress = 4\nvalue = 200\n", "t.toml");
	ASSERT_TRUE(ok.ok());
	ASSERT_EQ(ok.settings.depth.sr2Registers.size(), 1u);
	EXPECT_EQ(ok.settings.depth.sr2Registers[0], (Sr2RegisterWrite{ 4, 200 }));

	EXPECT_EQ(errorsOf("[[depth.sr2_register]]\naddress = 4\n"),
		  Errors{ "t.toml:1:1: depth.sr2_register[0].value: missing: the register value 0..255" });
	EXPECT_EQ(errorsOf("[[depth.sr2_register]]\naddress = 256\nvalue = 1\n"),
		  Errors{ "t.toml:2:11: depth.sr2_register[0].address: 256 is out of range: 0..255" });
	EXPECT_EQ(errorsOf("[[depth.sr2_register]]\naddress = 1\nvalue = 1\nvalu = 2\n"),
		  Errors{ "t.toml:4:1: depth.sr2_register[0].valu: unknown key (did you mean \"value\"?)" });
}

TEST(DeviceConfig, RangesMustBeOrdered)
{
	EXPECT_EQ(errorsOf("[depth]\nmin_mm = 500\nmax_mm = 500\n"),
		  Errors{ "t.toml:3:10: depth.max_mm: min_mm (500) must be less than max_mm (500)" });
	EXPECT_EQ(errorsOf("[depth]\nintensity_low = 9000\nintensity_high = 8000\n"),
		  Errors{ "t.toml:3:18: depth.intensity_high: intensity_low must be less than intensity_high" });
	EXPECT_EQ(errorsOf("[depth]\nscale_mm = 0.0\n"),
		  Errors{ "t.toml:2:12: depth.scale_mm: 0 is out of range: 0.01..100" });
}

TEST(DeviceConfig, TwoLedsCannotShareALine)
{
	EXPECT_EQ(errorsOf("[leds]\nerror_line = 1\n"),
		  Errors{ "t.toml:2:14: leds.error_line: error_line and depth_line use the same line 1" });
	// Unfitted LEDs (-1) may repeat.
	EXPECT_EQ(errorsOf("[leds]\nreader_line = -1\nerror_line = -1\n"), Errors{});
}

TEST(DeviceConfig, BackendsAreListed)
{
	EXPECT_EQ(errorsOf("[colour]\nbackend = \"v4l2\"\npixel_format = \"nv12\"\n"
			   "[depth]\nbackend = \"v4l2\"\npixel_format = \"y16\"\n"
			   "[leds]\nbackend = \"gpiod\"\n"),
		  Errors{});
	EXPECT_EQ(errorsOf("[colour]\npixel_format = \"rgb\"\n"),
		  Errors{ "t.toml:2:16: colour.pixel_format: \"rgb\" is not one of \"auto\" \"yuyv\" "
			  "\"nv12\" \"mjpeg\"" });
}
