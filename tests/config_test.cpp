// Config loading: the shipped file, a custom file, and each class of error
// with the exact place a technician is sent to.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "config/config_loader.hpp"
#include "config/toml_binder.hpp"
#include "tests/test_paths.hpp"

namespace depthkey {

// So that a failed EXPECT_EQ shows the error as the technician would see it.
void PrintTo(const ConfigError &error, std::ostream *os)
{
	*os << error.toString();
}

namespace {

const std::string kFile = "test.toml";

std::string defaultConfigPath()
{
	return test::sourceDir() + "/config/depthkey.toml";
}

std::string readFile(const std::string &path)
{
	std::ifstream in(path);
	std::stringstream text;
	text << in.rdbuf();
	return text.str();
}

// The single error a text produces, or a failure when it produces other than one.
ConfigError onlyError(std::string_view text)
{
	ConfigResult result = parseConfig(text, kFile);
	if (result.errors.size() != 1) {
		ADD_FAILURE() << result.errors.size() << " errors, expected 1";
		for (const ConfigError &e : result.errors)
			ADD_FAILURE() << e.toString();
	}
	return result.errors.empty() ? ConfigError{} : result.errors[0];
}

TEST(ConfigLoader, DefaultFileLoadsAsSettingsDefaults)
{
	ConfigResult result = loadConfig(defaultConfigPath());
	for (const ConfigError &e : result.errors)
		ADD_FAILURE() << e.toString();
	EXPECT_TRUE(result.ok());
	EXPECT_EQ(result.settings, Settings{});
}

TEST(ConfigLoader, DefaultFileShowsEveryKey)
{
	Settings settings;
	TomlBindResult bound = bindToml(readFile(defaultConfigPath()), "depthkey.toml",
					[&](TomlSection &root) { bindSettings(root, settings); });
	EXPECT_TRUE(bound.errors.empty());
	for (const std::string &key : bound.absent)
		ADD_FAILURE() << "config/depthkey.toml lacks " << key;
}

TEST(ConfigLoader, EmptyFileGivesDefaults)
{
	ConfigResult result = parseConfig("", kFile);
	EXPECT_TRUE(result.ok());
	EXPECT_EQ(result.settings, Settings{});
}

TEST(ConfigLoader, CustomFileSetsEveryField)
{
	ConfigResult result = parseConfig(R"(
[daemon]
log_level = "debug"
snapshot_dir = "/var/lib/depthkey/snapshots"
record_dir = "/srv/recordings/today"
record_compression = 6
[colour]
backend = "v4l2"
device = "/dev/v4l/by-id/usb-cam"
width = 1280
height = 720
fps = 30
pixel_format = "mjpeg"
timeout_ms = 2000
[depth]
backend = "sr2"
fps = 15
timeout_ms = 500
min_mm = 400
max_mm = 5000
usb_path = "1-2.3"
integration_time = 90
auto_integration = true
intensity_low = 12000
intensity_high = 20000
device = "usb-Intel_RealSense-video-index0"
width = 848
height = 480
pixel_format = "y16"
scale_mm = 0.125
[[depth.sr2_register]]
address = 0x0A
value = 7
[[depth.sr2_register]]
address = 0x0B
value = 255
[pairing]
offset_ms = -40
max_skew_ms = 80
delay_ms = 0
[segmentation]
near_mm = 800
far_mm = 2500
[composite]
opacity = 1
[board]
backend = "v4l2"
colour = "#FF8000"
image = "/srv/board.png"
device = "/dev/video4"
width = 1280
height = 720
fps = 30
pixel_format = "mjpeg"
timeout_ms = 3000
output_width = 1920
output_height = 1080
homography_file = "/var/lib/depthkey/board.toml"
[output]
composite_name = "/room12.composite"
lecturer_name = "/room12.lecturer"
board_lecturer_name = "/room12.lecturer.board"
slots = 5
group = "video"
v4l2_device = "/dev/video10"
[leds]
backend = "gpiod"
chip = "/dev/gpiochip1"
active_low = true
power_line = 10
depth_line = 11
colour_line = 12
calibration_line = 13
reader_line = -1
error_line = 15
board_line = 7
[sim]
seed = 9007199254740993
board_distance_mm = 2400
walk_speed_mps = 1.5
table = false
board_changes = false
lighting_change = false
lighting_amplitude = 0.3
lighting_period_s = 60
colour_noise = 0
colour_jitter_ms = 0
distortion = false
baseline_mm = 80
depth_noise = false
tof_amplitude = 9000
tof_corner_amplitude = 0.2
tof_ambient = 1000
halo_width_px = 0
halo_strength = 0.25
saturation_mm = 0
motion_blur = false
tof_exposure_ms = 10
depth_latency_ms = 0
depth_jitter_ms = 0
[replay]
path = "/srv/recordings/lecture1"
realtime = false
loop = false
)",
					  kFile);
	for (const ConfigError &e : result.errors)
		ADD_FAILURE() << e.toString();

	Settings expected;
	expected.daemon = { "debug", "/var/lib/depthkey/snapshots", "/srv/recordings/today", 6 };
	expected.colour = { "v4l2", "/dev/v4l/by-id/usb-cam", 1280, 720, 30, "mjpeg", 2000 };
	expected.depth = { "sr2", 15, 500, 400, 5000, "1-2.3", 90, true, 12000, 20000,
			   { { 0x0A, 7 }, { 0x0B, 255 } }, "usb-Intel_RealSense-video-index0",
			   848, 480, "y16", 0.125 };
	expected.pairing = { -40, false, 80, 0 };
	expected.segmentation = { 800, 2500 };
	expected.composite = { 1.0 };
	expected.board = { "v4l2", 0xff8000, "/srv/board.png", "/dev/video4", 1280, 720, 30, "mjpeg", 3000,
			   1920, 1080, "/var/lib/depthkey/board.toml" };
	expected.output = { "/room12.composite", "/room12.lecturer", "/room12.lecturer.board", 5, "video",
			    "/dev/video10" };
	expected.leds = { "gpiod", "/dev/gpiochip1", true, 10, 11, 12, 13, -1, 15, 7 };
	expected.sim = { 9007199254740993u, 2400, 1.5, false, false, false, 0.3, 60.0, 0.0, 0.0, false, 80,
			 false, 9000.0, 0.2, 1000.0, 0, 0.25, 0, false, 10.0, 0.0, 0.0 };
	expected.replay = { "/srv/recordings/lecture1", false, false };
	EXPECT_EQ(result.settings, expected);

	// Every section the file can change did change.
	const Settings defaults;
	EXPECT_NE(expected.daemon, defaults.daemon);
	EXPECT_NE(expected.colour, defaults.colour);
	EXPECT_NE(expected.depth, defaults.depth);
	EXPECT_NE(expected.pairing, defaults.pairing);
	EXPECT_NE(expected.leds, defaults.leds);
	EXPECT_NE(expected.segmentation, defaults.segmentation);
	EXPECT_NE(expected.composite, defaults.composite);
	EXPECT_NE(expected.output, defaults.output);
	EXPECT_NE(expected.sim, defaults.sim);
	EXPECT_NE(expected.replay, defaults.replay);
}

TEST(ConfigLoader, RetiredKeyingShareStillLoadsAndIsRangeChecked)
{
	// Retired (issue 28), but a config kept in /etc that still has it loads.
	EXPECT_TRUE(parseConfig("[daemon]\nkeying_share = 75\n", kFile).errors.empty());
	ConfigError e = onlyError("[daemon]\nkeying_share = 5\n");
	EXPECT_EQ(e.key, "daemon.keying_share");
	EXPECT_NE(e.message.find("10..100"), std::string::npos) << e.message;
	EXPECT_EQ(onlyError("[daemon]\nkeying_share = 101\n").key, "daemon.keying_share");
}

TEST(ConfigLoader, SimRangesAreChecked)
{
	ConfigError e = onlyError("[sim]\nboard_distance_mm = 1000\n");
	EXPECT_EQ(e.key, "sim.board_distance_mm");
	EXPECT_NE(e.message.find("out of range"), std::string::npos) << e.message;
	e = onlyError("[sim]\nhalo_strength = 1.5\n");
	EXPECT_EQ(e.key, "sim.halo_strength");
	EXPECT_EQ(e.line, 2);
	e = onlyError("[sim]\nmotion_blur = 1\n");
	EXPECT_EQ(e.key, "sim.motion_blur");
}

TEST(ConfigLoader, ReplayBackendNeedsAPath)
{
	ConfigError e = onlyError("[colour]\nbackend = \"replay\"\n");
	EXPECT_EQ(e.key, "replay.path");
	EXPECT_NE(e.message.find("must name the recorded folder"), std::string::npos) << e.message;
	ConfigResult ok = parseConfig("[depth]\nbackend = \"replay\"\n[replay]\npath = \"/srv/rec\"\n", kFile);
	EXPECT_TRUE(ok.ok());
	EXPECT_EQ(ok.settings.depth.backend, "replay");
	EXPECT_EQ(onlyError("[replay]\npath = \"rec\"\n").key, "replay.path");
}

TEST(ConfigLoader, ErrorFormat)
{
	EXPECT_EQ((ConfigError{ "a.toml", 3, 7, "colour.fps", "61 is out of range: 1..60" })
			  .toString(),
		  "a.toml:3:7: colour.fps: 61 is out of range: 1..60");
	EXPECT_EQ((ConfigError{ "a.toml", 2, 5, "", "bad" }).toString(), "a.toml:2:5: bad");
	EXPECT_EQ((ConfigError{ "a.toml", 0, 0, "", "cannot open" }).toString(),
		  "a.toml: cannot open");
}

TEST(ConfigLoader, SyntaxErrorHasItsPosition)
{
	ConfigError e = onlyError("[colour]\nwidth = 640\nheight = = 480\n");
	EXPECT_EQ(e.file, kFile);
	EXPECT_EQ(e.line, 3);
	EXPECT_EQ(e.column, 10);
	EXPECT_EQ(e.key, "");
	EXPECT_NE(e.message.find("value"), std::string::npos) << e.message;
}

TEST(ConfigLoader, UnknownKeySuggestsTheNearestOne)
{
	EXPECT_EQ(onlyError("[segmentation]\nnear_mm = 600\n  near_nm = 700\n"),
		  (ConfigError{ kFile, 3, 3, "segmentation.near_nm",
				"unknown key (did you mean \"near_mm\"?)" }));
	EXPECT_EQ(onlyError("[sim]\nvolume = 3\n"),
		  (ConfigError{ kFile, 2, 1, "sim.volume", "unknown key" }));
	EXPECT_EQ(onlyError("verbose = true\n"),
		  (ConfigError{ kFile, 1, 1, "verbose", "unknown key" }));
}

TEST(ConfigLoader, UnknownSection)
{
	EXPECT_EQ(onlyError("[daemon]\nlog_level = \"info\"\n\n[segmentaton]\nnear_mm = 600\n"),
		  (ConfigError{ kFile, 4, 2, "segmentaton",
				"unknown section (did you mean \"segmentation\"?)" }));
	EXPECT_EQ(onlyError("[colour.lens]\nzoom = 2\n"),
		  (ConfigError{ kFile, 1, 9, "colour.lens", "unknown section" }));
	EXPECT_EQ(onlyError("[[registers]]\naddress = 1\n"),
		  (ConfigError{ kFile, 1, 3, "registers", "unknown section" }));
}

TEST(ConfigLoader, WrongType)
{
	EXPECT_EQ(onlyError("[colour]\nwidth = \"640\"\n"),
		  (ConfigError{ kFile, 2, 9, "colour.width", "expected an integer, got a string" }));
	EXPECT_EQ(onlyError("[segmentation]\nnear_mm = 500.0\n"),
		  (ConfigError{ kFile, 2, 11, "segmentation.near_mm",
				"expected an integer, got a floating-point number" }));
	EXPECT_EQ(onlyError("[composite]\nopacity = \"half\"\n"),
		  (ConfigError{ kFile, 2, 11, "composite.opacity", "expected a number, got a string" }));
	EXPECT_EQ(onlyError("[output]\ngroup = 44\n"),
		  (ConfigError{ kFile, 2, 9, "output.group", "expected a string, got an integer" }));
	EXPECT_EQ(onlyError("colour = 3\n"),
		  (ConfigError{ kFile, 1, 10, "colour", "expected a table ([colour]), got an integer" }));
}

TEST(ConfigLoader, OutOfRange)
{
	EXPECT_EQ(onlyError("[colour]\nfps = 61\n"),
		  (ConfigError{ kFile, 2, 7, "colour.fps", "61 is out of range: 1..60" }));
	EXPECT_EQ(onlyError("[segmentation]\nnear_mm = 299\n"),
		  (ConfigError{ kFile, 2, 11, "segmentation.near_mm", "299 is out of range: 300..7500" }));
	EXPECT_EQ(onlyError("[composite]\nopacity = 1.5\n"),
		  (ConfigError{ kFile, 2, 11, "composite.opacity", "1.5 is out of range: 0..1" }));
	EXPECT_EQ(onlyError("[composite]\nopacity = nan\n"),
		  (ConfigError{ kFile, 2, 11, "composite.opacity", "nan is out of range: 0..1" }));
	EXPECT_EQ(onlyError("[sim]\nseed = -1\n"),
		  (ConfigError{ kFile, 2, 8, "sim.seed", "-1 is out of range: must be at least 0" }));
	EXPECT_EQ(onlyError("[board]\ncolour = 0x1000000\n"),
		  (ConfigError{ kFile, 2, 10, "board.colour",
				"16777216 is not a colour: expected 0x000000..0xffffff" }));
	EXPECT_EQ(onlyError("[board]\ncolour = \"#12345\"\n"),
		  (ConfigError{ kFile, 2, 10, "board.colour",
				"\"#12345\" is not a colour: expected \"#rrggbb\"" }));
}

TEST(ConfigLoader, ValueNotAllowed)
{
	EXPECT_EQ(onlyError("[depth]\nbackend = \"kinect\"\n"),
		  (ConfigError{ kFile, 2, 11, "depth.backend",
				"\"kinect\" is not one of \"sim\" \"sr2\" \"v4l2\" \"replay\"" }));
	EXPECT_EQ(onlyError("[daemon]\nlog_level = \"verbose\"\n"),
		  (ConfigError{ kFile, 2, 13, "daemon.log_level",
				"\"verbose\" is not one of \"error\" \"warning\" \"info\" \"debug\"" }));
	EXPECT_EQ(onlyError("[daemon]\nsnapshot_dir = \"snaps\"\n"),
		  (ConfigError{ kFile, 2, 16, "daemon.snapshot_dir",
				"\"snaps\" must be an absolute path" }));
}

TEST(ConfigLoader, NearMustBeLessThanFar)
{
	EXPECT_EQ(onlyError("[segmentation]\nnear_mm = 1600\nfar_mm = 1600\n"),
		  (ConfigError{ kFile, 3, 10, "segmentation.far_mm",
				"near_mm (1600) must be less than far_mm (1600)" }));
	// Against the default far_mm (1850): the key that is in the file is blamed.
	EXPECT_EQ(onlyError("[segmentation]\nnear_mm = 2000\n"),
		  (ConfigError{ kFile, 2, 11, "segmentation.near_mm",
				"near_mm (2000) must be less than far_mm (1850)" }));
	// An invalid value is reported once, not again as a cross-field error.
	EXPECT_EQ(onlyError("[segmentation]\nnear_mm = 9000\nfar_mm = 400\n").key,
		  "segmentation.near_mm");
}

TEST(ConfigLoader, SharedMemoryNames)
{
	const char *expected = "must be \"/name\": a leading '/', then letters, digits, '.', '_' or '-'";
	const char *charset = "may hold only letters, digits, '.', '_' and '-' after its leading '/'";
	EXPECT_EQ(onlyError("[output]\ncomposite_name = \"depthkey\"\n"),
		  (ConfigError{ kFile, 2, 18, "output.composite_name",
				"\"depthkey\" " + std::string(expected) }));
	EXPECT_EQ(onlyError("[output]\nlecturer_name = \"/dk/lecturer\"\n"),
		  (ConfigError{ kFile, 2, 17, "output.lecturer_name",
				"\"/dk/lecturer\" " + std::string(charset) }));
	EXPECT_EQ(onlyError("[output]\nlecturer_name = \"/\"\n").key, "output.lecturer_name");
	EXPECT_EQ(onlyError("[output]\nlecturer_name = \"/depthkey.composite\"\n"),
		  (ConfigError{ kFile, 2, 17, "output.lecturer_name",
				"composite_name and lecturer_name must differ" }));
	EXPECT_EQ(onlyError("[output]\ngroup = \"video staff\"\n").message,
		  "\"video staff\" is not a group name");
}

TEST(ConfigLoader, V4l2OutputIsADeviceNodeThatNoCameraUses)
{
	EXPECT_EQ(parseConfig("[output]\nv4l2_device = \"/dev/video10\"\n", kFile).settings.output.v4l2Device,
		  "/dev/video10");
	EXPECT_EQ(Settings{}.output.v4l2Device, "") << "off by default";
	EXPECT_EQ(onlyError("[output]\nv4l2_device = \"video10\"\n"),
		  (ConfigError{ kFile, 2, 15, "output.v4l2_device",
				"\"video10\" must be \"\" (off) or a device path under /dev, e.g. \"/dev/video10\"" }));
	EXPECT_EQ(onlyError("[output]\n\nv4l2_device = \"/tmp/video10\"\n").line, 3);
	EXPECT_EQ(onlyError("[colour]\nbackend = \"v4l2\"\ndevice = \"/dev/video10\"\n"
			    "[output]\nv4l2_device = \"/dev/video10\"\n"),
		  (ConfigError{ kFile, 5, 15, "output.v4l2_device",
				"is colour.device, the camera the daemon captures from; use a v4l2loopback node" }));
	// The sim colour camera has no device: /dev/video0 is free for the webcam.
	EXPECT_TRUE(parseConfig("[output]\nv4l2_device = \"/dev/video0\"\n", kFile).ok());
	// Only the webcam changed: the shared memory stays as it is.
	OutputSettings a, b;
	b.v4l2Device = "/dev/video10";
	EXPECT_TRUE(sameSharedMemory(a, b));
	b.slots = 4;
	EXPECT_FALSE(sameSharedMemory(a, b));
}

TEST(ConfigLoader, AllErrorsAreReportedInFileOrder)
{
	ConfigResult result = parseConfig(R"([colour]
width = 8
fps = "fast"
[segmentation]
near_mm = 1200
far_mm = 1000
[ouptut]
slots = 4
[sim]
seed = 1.5
)",
					  kFile);
	std::vector<std::pair<int, std::string>> got;
	for (const ConfigError &e : result.errors)
		got.emplace_back(e.line, e.key);
	EXPECT_EQ(got, (std::vector<std::pair<int, std::string>>{
			       { 2, "colour.width" },
			       { 3, "colour.fps" },
			       { 6, "segmentation.far_mm" },
			       { 7, "ouptut" },
			       { 10, "sim.seed" },
		       }));
	// Valid keys in a file with errors still bind; invalid ones keep defaults.
	EXPECT_EQ(result.settings.segmentation.nearMm, 1200);
	EXPECT_EQ(result.settings.colour.width, Settings{}.colour.width);
}

TEST(ConfigLoader, MissingFileNamesThePath)
{
	const std::string path = "/nonexistent/depthkey.toml";
	ConfigResult result = loadConfig(path);
	ASSERT_EQ(result.errors.size(), 1u);
	EXPECT_EQ(result.errors[0].file, path);
	EXPECT_EQ(result.errors[0].toString(),
		  path + ": cannot read config file: No such file or directory");
	EXPECT_EQ(result.settings, Settings{});
}

TEST(ConfigLoader, DirectoryIsNotAConfigFile)
{
	ConfigResult result = loadConfig("/");
	ASSERT_EQ(result.errors.size(), 1u);
	EXPECT_EQ(result.errors[0].toString(), "/: cannot read config file: not a regular file (a directory)");
}

// The binder's nesting, for the sections still to come (calibration tables,
// SR-2 register writes as an array of tables).
struct Register {
	uint16_t address = 0;
	uint32_t value = 0;
};

TEST(ConfigBinder, NestedTablesAndArraysOfTables)
{
	int64_t offset = 0;
	bool enabled = false;
	std::vector<Register> registers;
	TomlBindResult bound = bindToml(R"(
[camera.calibration]
offset = -12
[[camera.register]]
address = 0x10
value = 0xdeadbeef
[[camera.register]]
address = 0x10000
vaule = 1
)",
					kFile, [&](TomlSection &root) {
		root.table("camera", [&](TomlSection &camera) {
			camera.table("calibration", [&](TomlSection &cal) {
				cal.integer("offset", offset, -100, 100);
				cal.boolean("enabled", enabled);
			});
			camera.tables("register", [&](TomlSection &reg, size_t) {
				Register r;
				reg.integer("address", r.address, 0, 0xffff);
				reg.integer("value", r.value, 0, 0xffffffff);
				registers.push_back(r);
			});
		});
	});

	EXPECT_EQ(offset, -12);
	ASSERT_EQ(registers.size(), 2u);
	EXPECT_EQ(registers[0].address, 0x10);
	EXPECT_EQ(registers[0].value, 0xdeadbeefu);
	EXPECT_EQ(bound.errors,
		  (std::vector<ConfigError>{
			  { kFile, 8, 11, "camera.register[1].address",
			    "65536 is out of range: 0..65535" },
			  { kFile, 9, 1, "camera.register[1].vaule",
			    "unknown key (did you mean \"value\"?)" },
		  }));
	EXPECT_EQ(bound.absent, (std::vector<std::string>{ "camera.calibration.enabled",
							     "camera.register[1].value" }));
}

TEST(ConfigLoader, DepthOffsetIsAnIntegerOrAuto)
{
	ConfigResult automatic = parseConfig("[pairing]\noffset_ms = \"auto\"\n", kFile);
	ASSERT_TRUE(automatic.ok());
	EXPECT_TRUE(automatic.settings.pairing.offsetAuto);
	ConfigResult fixed = parseConfig("[pairing]\noffset_ms = -60\ndelay_ms = 0\n", kFile);
	ASSERT_TRUE(fixed.ok());
	EXPECT_FALSE(fixed.settings.pairing.offsetAuto);
	EXPECT_EQ(fixed.settings.pairing.offsetMs, -60);
	EXPECT_EQ(fixed.settings.pairing.delayMs, 0);
	EXPECT_EQ(onlyError("[pairing]\noffset_ms = \"soon\"\n"),
		  (ConfigError{ kFile, 2, 13, "pairing.offset_ms",
				"\"soon\" is not allowed: expected an integer or \"auto\"" }));
	EXPECT_EQ(onlyError("[pairing]\noffset_ms = 1.5\n"),
		  (ConfigError{ kFile, 2, 13, "pairing.offset_ms",
				"expected an integer or \"auto\", got a floating-point number" }));
	EXPECT_EQ(onlyError("[pairing]\ndelay_ms = 1001\n"),
		  (ConfigError{ kFile, 2, 12, "pairing.delay_ms", "1001 is out of range: 0..1000" }));
}

// Issue 31 point 7: offsets inside -1000..1000 that can never pair (no depth
// frame is captured in time, or none is kept that old) are refused at the key.
TEST(ConfigLoader, DepthOffsetThatCanNeverPairIsRefused)
{
	// Defaults: delay 150, max skew 150, colour 25 fps, depth 10 fps: -340..750.
	EXPECT_TRUE(parseConfig("[pairing]\noffset_ms = -340\n", kFile).ok());
	EXPECT_TRUE(parseConfig("[pairing]\noffset_ms = 750\n", kFile).ok());
	EXPECT_EQ(onlyError("[pairing]\noffset_ms = -1000\n"),
		  (ConfigError{ kFile, 2, 13, "pairing.offset_ms",
				"-1000 can never pair: with delay_ms 150, max_skew_ms 150 and the "
				"cameras' fps only -340..750 can" }));
	EXPECT_EQ(onlyError("[pairing]\noffset_ms = 1000\n"),
		  (ConfigError{ kFile, 2, 13, "pairing.offset_ms",
				"1000 can never pair: with delay_ms 150, max_skew_ms 150 and the "
				"cameras' fps only -340..750 can" }));
	// The range follows the rates and the window: 30 fps depth keeps 200 ms.
	EXPECT_FALSE(parseConfig("[depth]\nfps = 30\n[pairing]\noffset_ms = 400\n", kFile).ok());
	EXPECT_TRUE(parseConfig("[pairing]\noffset_ms = -900\ndelay_ms = 700\nmax_skew_ms = 200\n", kFile).ok());
	// "auto" is measured within its own window.
	EXPECT_TRUE(parseConfig("[pairing]\noffset_ms = \"auto\"\ndelay_ms = 0\n", kFile).ok());
}

} // namespace

} // namespace depthkey
