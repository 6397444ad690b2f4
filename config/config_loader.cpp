// The depthkey config schema, one function per section, and file loading.
#include "config/config_loader.hpp"

#include <cerrno>
#include <cstring>
#include <grp.h>
#include <limits>
#include <sys/stat.h>
#include <unistd.h>

#include "config/file_format.hpp"
#include "config/listen_address.hpp"
#include "config/frame_limits.hpp"
#include "config/text_file.hpp"
#include "config/toml_binder.hpp"
#include "algo/frame_pairer.hpp"
#include "hal/shm_name.hpp"

namespace depthkey {

namespace {

// The values each enumeration accepts. Adding a backend ("sr2", "v4l2",
// "replay") is one edit here, once the daemon can build it.
constexpr std::string_view kLogLevels[] = { "error", "warning", "info", "debug" };
constexpr std::string_view kColourBackends[] = { "sim", "v4l2", "replay" };
constexpr std::string_view kDepthBackends[] = { "sim", "sr2", "v4l2", "replay" };
constexpr std::string_view kLedBackends[] = { "none", "gpiod" };
constexpr std::string_view kColourFormats[] = { "auto", "yuyv", "nv12", "mjpeg" };
constexpr std::string_view kDepthFormats[] = { "z16", "y16" };
constexpr std::string_view kBoardBackends[] = { "colour", "image", "v4l2", "sim" };

constexpr int kMinRangeMm = 300;        // nearest the depth camera measures
constexpr int kMaxRangeMm = 7500;       // furthest it measures

bool hasNul(std::string_view s)
{
	return s.find('\0') != std::string_view::npos;
}

std::string checkAbsolutePath(std::string_view path)
{
	if (path.empty() || path[0] != '/' || hasNul(path))
		return "must be an absolute path";
	return "";
}

// A video device: an absolute path, or a bare name under /dev/v4l/by-id/.
std::string checkVideoDevice(std::string_view device)
{
	if (!device.empty() && device[0] != '/' && device.find('/') == std::string_view::npos &&
	    !hasNul(device) && device != "." && device != "..")
		return "";
	return checkAbsolutePath(device).empty()
		       ? ""
		       : "must be an absolute path or a name in /dev/v4l/by-id/";
}

// A USB port path as sysfs and lsusb -t show it: BUS-PORT[.PORT...], e.g. "1-2.3".
std::string checkUsbPath(std::string_view path)
{
	if (path.empty())
		return "";
	size_t dash = path.find('-');
	bool ok = dash != std::string_view::npos && dash > 0 && dash + 1 < path.size();
	for (size_t i = 0; ok && i < path.size(); i++) {
		char c = path[i];
		bool sep = i == dash || (i > dash && c == '.');
		ok = sep ? (i + 1 < path.size() && path[i + 1] != '.') : (c >= '0' && c <= '9');
	}
	return ok ? "" : "must be \"\" or a USB port path BUS-PORT[.PORT...], e.g. \"1-2.3\"";
}

// "gpiochip0", "/dev/gpiochip0", a chip label or number, as libgpiod looks it up.
std::string checkGpioChip(std::string_view chip)
{
	return chip.empty() || hasNul(chip) ? "must name a GPIO chip, e.g. \"gpiochip0\"" : "";
}
// The daemon runs from / under systemd, so a relative path would land
// somewhere nobody looks.
std::string checkOptionalAbsolutePath(std::string_view path)
{
	return path.empty() ? "" : checkAbsolutePath(path);
}

// The rule ShmRingWriter::open() applies (hal/shm_name.hpp): a name that
// passes here is one the daemon can create.
std::string checkShmName(std::string_view name)
{
	return shmNameProblem(name);
}

// "" (the daemon's own group) or a plain group name, as useradd accepts,
// of a group this system has: a misspelt group would otherwise pass
// --check-config and only fail when the output is opened (on a reload,
// after the old output was dropped). Whether the daemon's user may chgrp to
// it is checked at open, and a reload that cannot open keeps the old output.
std::string checkGroupName(std::string_view group)
{
	if (group.empty())
		return "";
	bool plain = group.size() <= 32 && group[0] != '-' &&
		     group.find_first_not_of("abcdefghijklmnopqrstuvwxyz"
					     "ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_.-") ==
			     std::string_view::npos;
	if (!plain)
		return "is not a group name";
	// ShmRingWriter takes an all-digit name as a gid, so does the check.
	if (group.find_first_not_of("0123456789") == std::string_view::npos)
		return "";
	std::string name(group);
	std::vector<char> buffer(1024);
	struct group entry{};
	struct group *found = nullptr;
	int ret;
	while ((ret = getgrnam_r(name.c_str(), &entry, buffer.data(), buffer.size(), &found)) == ERANGE &&
	       buffer.size() < (1u << 20))
		buffer.resize(buffer.size() * 2);
	if (ret)
		return std::string("cannot be looked up: ") + std::strerror(ret);
	return found ? "" : "is not a group on this system (see getent group)";
}

void bindDaemon(TomlSection &sec, DaemonSettings &s)
{
	sec.string("log_level", s.logLevel, kLogLevels);
	sec.string("snapshot_dir", s.snapshotDir, checkOptionalAbsolutePath);
	sec.string("record_dir", s.recordDir, checkOptionalAbsolutePath);
	sec.integer("record_compression", s.recordCompression, 0, 9);
	// Retired with the token bucket when keying left the loop (issue 28):
	// still accepted (10..100) so that a kept /etc config loads, bound only
	// when present so that it is no longer listed as a default.
	int retiredKeyingShare = 0;
	if (sec.has("keying_share"))
		sec.integer("keying_share", retiredKeyingShare, 10, 100);
}

void bindColour(TomlSection &sec, ColourCameraSettings &s)
{
	sec.string("backend", s.backend, kColourBackends);
	sec.string("device", s.device, checkVideoDevice);
	sec.integer("width", s.width, 16, kMaxFrameWidth);
	sec.integer("height", s.height, 16, kMaxFrameHeight);
	sec.integer("fps", s.fps, 1, 60);
	sec.string("pixel_format", s.pixelFormat, kColourFormats);
	sec.integer("timeout_ms", s.timeoutMs, 100, 10000);
}

void bindSr2Register(TomlSection &sec, DepthCameraSettings &s)
{
	Sr2RegisterWrite write;
	bool ok = sec.integer("address", write.address, 0, 255);
	ok = sec.integer("value", write.value, 0, 255) && ok;
	// Both are required: a write without an address would silently hit 0x00.
	sec.require(sec.has("address"), "address", "missing: the register address 0..255");
	sec.require(sec.has("value"), "value", "missing: the register value 0..255");
	if (ok && sec.has("address") && sec.has("value"))
		s.sr2Registers.push_back(write);
}

void bindDepth(TomlSection &sec, DepthCameraSettings &s)
{
	sec.string("backend", s.backend, kDepthBackends);
	sec.integer("fps", s.fps, 1, 60);
	sec.integer("timeout_ms", s.timeoutMs, 100, 10000);
	bool ok = sec.integer("min_mm", s.minMm, 0, 65535);
	ok = sec.integer("max_mm", s.maxMm, 1, 65535) && ok;
	if (ok)
		sec.require(s.minMm < s.maxMm, sec.has("max_mm") ? "max_mm" : "min_mm",
			    "min_mm (" + std::to_string(s.minMm) + ") must be less than max_mm (" +
				    std::to_string(s.maxMm) + ")");
	sec.string("usb_path", s.usbPath, checkUsbPath);
	sec.integer("integration_time", s.integrationTime, 0, 255);
	sec.boolean("auto_integration", s.autoIntegration);
	ok = sec.integer("intensity_low", s.intensityLow, 0, 65535);
	ok = sec.integer("intensity_high", s.intensityHigh, 0, 65535) && ok;
	if (ok)
		sec.require(s.intensityLow < s.intensityHigh,
			    sec.has("intensity_high") ? "intensity_high" : "intensity_low",
			    "intensity_low must be less than intensity_high");
	sec.tables("sr2_register", [&](TomlSection &element, size_t) { bindSr2Register(element, s); });
	sec.string("device", s.device, checkVideoDevice);
	sec.integer("width", s.width, 16, kMaxFrameWidth);
	sec.integer("height", s.height, 16, kMaxFrameHeight);
	sec.string("pixel_format", s.pixelFormat, kDepthFormats);
	sec.number("scale_mm", s.scaleMm, 0.01, 100.0);
}

// Bound after [colour] and [depth]: their rates set the offsets that can pair.
void bindPairing(TomlSection &sec, PairingSettings &s, int colourFps, int depthFps)
{
	bool ok = sec.integerOrWord("offset_ms", s.offsetMs, -1000, 1000, "auto", s.offsetAuto);
	ok = sec.integer("max_skew_ms", s.maxSkewMs, 1, 1000) && ok;
	ok = sec.integer("delay_ms", s.delayMs, 0, 1000) && ok;
	const PairableOffsets range = pairableOffsetsMs(s.maxSkewMs, s.delayMs, colourFps, depthFps);
	if (ok && !s.offsetAuto)
		sec.require(s.offsetMs >= range.minMs && s.offsetMs <= range.maxMs, "offset_ms",
			    std::to_string(s.offsetMs) + " can never pair: with delay_ms " +
				    std::to_string(s.delayMs) + ", max_skew_ms " + std::to_string(s.maxSkewMs) +
				    " and the cameras' fps only " + std::to_string(range.minMs) + ".." +
				    std::to_string(range.maxMs) + " can");
}

void bindSegmentation(TomlSection &sec, SegmentationSettings &s)
{
	bool ok = sec.integer("near_mm", s.nearMm, kMinRangeMm, kMaxRangeMm);
	ok = sec.integer("far_mm", s.farMm, kMinRangeMm, kMaxRangeMm) && ok;

	// Only compare values that were both accepted; blame the key the
	// technician wrote (far_mm when both are there).
	if (ok)
		sec.require(s.nearMm < s.farMm, sec.has("far_mm") ? "far_mm" : "near_mm",
			    "near_mm (" + std::to_string(s.nearMm) +
				    ") must be less than far_mm (" +
				    std::to_string(s.farMm) + ")");
	bool amplitudes = sec.integer("min_amplitude", s.minAmplitude, 0, 65535);
	amplitudes = sec.integer("max_amplitude", s.maxAmplitude, 1, 65535) && amplitudes;
	if (amplitudes)
		sec.require(s.minAmplitude < s.maxAmplitude,
			    sec.has("max_amplitude") ? "max_amplitude" : "min_amplitude",
			    "min_amplitude (" + std::to_string(s.minAmplitude) +
				    ") must be less than max_amplitude (" +
				    std::to_string(s.maxAmplitude) + ")");
	sec.integer("erode_px", s.erodePx, 0, 20);
	sec.integer("dilate_px", s.dilatePx, 1, 40);
	sec.integer("surface_px", s.surfacePx, 1, 40);
	sec.integer("core_px", s.corePx, 0, 20);
	sec.integer("halo_px", s.haloPx, 0, 20);
	sec.number("halo_share", s.haloShare, 0.0, 0.9);
}

void bindMapping(TomlSection &sec, MappingSettings &s)
{
	sec.string("calibration_file", s.calibrationFile, checkOptionalAbsolutePath);
}

void bindLearning(TomlSection &sec, LearningSettings &s)
{
	sec.integer("initial_frames", s.initialFrames, 1, 1000);
	sec.number("board_rate", s.boardRate, 0.0, 1.0);
	sec.number("lecturer_rate", s.lecturerRate, 0.0, 1.0);
	sec.integer("samples", s.samples, 256, 65536);
	sec.integer("margin_px", s.marginPx, 0, 40);
	sec.number("relearn_misfit", s.relearnMisfit, 0.0, 1.0);
}

void bindSiox(TomlSection &sec, SioxSettings &s)
{
	sec.integer("smoothing", s.smoothing, 0, 8);
	sec.boolean("soft_alpha", s.softAlpha);
	sec.integer("guided_radius", s.guidedRadius, 0, 7);
	sec.integer("guided_eps", s.guidedEps, 1, 65025);
}

void bindDecision(TomlSection &sec, DecisionSettings &s)
{
	sec.integer("depth_weight", s.depthWeight, 0, 255);
	sec.integer("depth_pivot", s.depthPivot, 1, 254);
	sec.integer("board_weight", s.boardWeight, 0, 255);
	sec.integer("board_match", s.boardMatch, 1, 255);
	sec.integer("temporal_weight", s.temporalWeight, 0, 255);
	sec.integer("still_colour", s.stillColour, 1, 255);
	sec.integer("cut_smoothness", s.cutSmoothness, 0, 10000);
	sec.integer("cut_edge_sigma", s.cutEdgeSigma, 1, 64);
	sec.integer("cut_max_band_pixels", s.cutMaxBandPixels, 0, 8294400);
	sec.integer("cut_levels", s.cutLevels, 0, 4);
	sec.integer("cut_margin", s.cutMargin, 0, 8);
	sec.integer("edge_unmixing", s.edgeUnmixing, 0, 195075);
}

void bindComposite(TomlSection &sec, CompositeSettings &s)
{
	sec.number("opacity", s.opacity, 0.0, 1.0);
	// The board's keys moved to [board]: say where, rather than "unknown"
	// (bound only when present, so that they are not listed as defaults).
	uint32_t oldColour = 0;
	std::string oldImage;
	if (sec.has("board_colour") && sec.colour("board_colour", oldColour))
		sec.require(false, "board_colour", "has moved: [board] colour (with backend = \"colour\")");
	if (sec.has("board_image") && sec.string("board_image", oldImage))
		sec.require(false, "board_image", "has moved: [board] image (with backend = \"image\")");
}

void bindBoard(TomlSection &sec, BoardSettings &s)
{
	sec.string("backend", s.backend, kBoardBackends);
	sec.colour("colour", s.colour);
	bool imageOk = sec.string("image", s.image, checkOptionalAbsolutePath);
	if (imageOk)
		sec.require(s.backend != "image" || !s.image.empty(), "image",
			    "must name the board's picture file when backend is \"image\"");
	sec.string("device", s.device, checkVideoDevice);
	sec.integer("width", s.width, 16, 3840);
	sec.integer("height", s.height, 16, 2160);
	sec.integer("fps", s.fps, 1, 60);
	sec.string("pixel_format", s.pixelFormat, kColourFormats);
	sec.integer("timeout_ms", s.timeoutMs, 100, 10000);
	bool ok = sec.integer("output_width", s.outputWidth, 0, 3840);
	ok = sec.integer("output_height", s.outputHeight, 0, 2160) && ok;
	// A size is scaled as a whole or not at all.
	if (ok)
		sec.require((s.outputWidth == 0) == (s.outputHeight == 0),
			    sec.has("output_height") ? "output_height" : "output_width",
			    "output_width and output_height must both be 0 (the picture's size) or both be set");
	if (ok && s.outputWidth)
		sec.require(s.outputWidth >= 16 && s.outputHeight >= 16,
			    sec.has("output_height") ? "output_height" : "output_width",
			    "an output size must be at least 16x16");
	sec.string("homography_file", s.homographyFile, checkOptionalAbsolutePath);
}

// The virtual webcam's node: "" or an absolute path under /dev (a
// v4l2loopback node, e.g. /dev/video10), not a camera the daemon captures from.
void bindV4l2Output(TomlSection &sec, const Settings &all, OutputSettings &s)
{
	bool ok = sec.string("v4l2_device", s.v4l2Device, [](std::string_view path) {
		if (path.empty())
			return std::string();
		if (!checkAbsolutePath(path).empty() || path.substr(0, 5) != "/dev/" || path.size() == 5)
			return std::string("must be \"\" (off) or a device path under /dev, e.g. \"/dev/video10\"");
		return std::string();
	});
	if (!ok || s.v4l2Device.empty())
		return;
	sec.require(!(all.colour.backend == "v4l2" && all.colour.device == s.v4l2Device), "v4l2_device",
		    "is colour.device, the camera the daemon captures from; use a v4l2loopback node");
	sec.require(!(all.board.backend == "v4l2" && all.board.device == s.v4l2Device), "v4l2_device",
		    "is board.device, the capture stick; use a v4l2loopback node");
	sec.require(!(all.depth.backend == "v4l2" && all.depth.device == s.v4l2Device), "v4l2_device",
		    "is depth.device, the depth camera; use a v4l2loopback node");
}

void bindOutput(TomlSection &sec, OutputSettings &s)
{
	bool ok = sec.string("composite_name", s.compositeName, checkShmName);
	ok = sec.string("lecturer_name", s.lecturerName, checkShmName) && ok;
	ok = sec.string("board_lecturer_name", s.boardLecturerName, checkShmName) && ok;
	sec.integer("slots", s.slots, 2, 8);
	sec.string("group", s.group, checkGroupName);

	// Both streams in one shared memory object would corrupt each other.
	if (ok)
	{
		sec.require(s.compositeName != s.lecturerName,
			    sec.has("lecturer_name") ? "lecturer_name" : "composite_name",
			    "composite_name and lecturer_name must differ");
		sec.require(s.boardLecturerName != s.compositeName && s.boardLecturerName != s.lecturerName,
			    "board_lecturer_name", "board_lecturer_name must differ from composite_name and lecturer_name");
	}
}

void bindPreview(TomlSection &sec, PreviewSettings &s)
{
	bool ok = sec.string("listen", s.listen, [](std::string_view text) {
		ListenAddress address;
		return text.empty() ? std::string() : parseListenAddress(text, address);
	});
	ok = sec.string("password_file", s.passwordFile, checkOptionalAbsolutePath) && ok;
	sec.integer("max_clients", s.maxClients, 1, 32);
	sec.integer("jpeg_quality", s.jpegQuality, 10, 100);
	// The box sits on a school network: beyond loopback only with a password.
	ListenAddress address;
	if (ok && !s.listen.empty() && parseListenAddress(s.listen, address).empty())
		sec.require(address.loopback || !s.passwordFile.empty(), "listen",
			    "'" + s.listen + "' is reachable from the network: set preview.password_file "
			    "(HTTP basic auth) or listen on 127.0.0.1 and use ssh -L");
}

void bindLeds(TomlSection &sec, LedSettings &s)
{
	sec.string("backend", s.backend, kLedBackends);
	sec.string("chip", s.chip, checkGpioChip);
	sec.boolean("active_low", s.activeLow);
	struct Line { const char *key; int &offset; };
	Line lines[] = { { "power_line", s.powerLine }, { "depth_line", s.depthLine },
			 { "colour_line", s.colourLine }, { "calibration_line", s.calibrationLine },
			 { "reader_line", s.readerLine }, { "error_line", s.errorLine },
			 { "board_line", s.boardLine } };
	bool ok = true;
	for (Line &line : lines)
		ok = sec.integer(line.key, line.offset, -1, 511) && ok;
	// Two LEDs on one line would show neither; blame the later key.
	for (size_t i = 0; ok && i < std::size(lines); i++)
		for (size_t j = 0; j < i; j++)
			if (lines[i].offset >= 0 && lines[i].offset == lines[j].offset) {
				sec.require(false, sec.has(lines[i].key) ? lines[i].key : lines[j].key,
					    std::string(lines[i].key) + " and " + lines[j].key +
						    " use the same line " + std::to_string(lines[i].offset));
				ok = false;
				break;
			}
}

void bindSim(TomlSection &sec, SimSettings &s)
{
	sec.integer("seed", s.seed, 0, std::numeric_limits<int64_t>::max());
	sec.integer("board_distance_mm", s.boardDistanceMm, 1500, 2500);
	sec.number("walk_speed_mps", s.walkSpeedMps, 0.1, 3.0);
	sec.boolean("table", s.table);
	sec.boolean("board_changes", s.boardChanges);
	sec.boolean("lighting_change", s.lightingChange);
	sec.number("lighting_amplitude", s.lightingAmplitude, 0.0, 0.5);
	sec.number("lighting_period_s", s.lightingPeriodS, 1.0, 600.0);
	sec.number("colour_noise", s.colourNoise, 0.0, 30.0);
	sec.number("colour_jitter_ms", s.colourJitterMs, 0.0, 20.0);
	sec.boolean("distortion", s.distortion);
	sec.integer("baseline_mm", s.baselineMm, 0, 200);
	sec.boolean("depth_noise", s.depthNoise);
	sec.number("tof_amplitude", s.tofAmplitude, 500.0, 30000.0);
	sec.number("tof_corner_amplitude", s.tofCornerAmplitude, 0.01, 1.0);
	sec.number("tof_ambient", s.tofAmbient, 0.0, 30000.0);
	sec.integer("halo_width_px", s.haloWidthPx, 0, 20);
	sec.number("halo_strength", s.haloStrength, 0.0, 1.0);
	sec.integer("saturation_mm", s.saturationMm, 0, 2000);
	sec.boolean("motion_blur", s.motionBlur);
	sec.number("tof_exposure_ms", s.tofExposureMs, 1.0, 100.0);
	sec.number("depth_latency_ms", s.depthLatencyMs, 0.0, 300.0);
	sec.number("depth_jitter_ms", s.depthJitterMs, 0.0, 50.0);
}

void bindReplay(TomlSection &sec, ReplaySettings &s, bool used)
{
	bool ok = sec.string("path", s.path, checkOptionalAbsolutePath);
	sec.boolean("realtime", s.realtime);
	sec.boolean("loop", s.loop);
	if (ok)
		sec.require(!used || !s.path.empty(), "path",
			    "must name the recorded folder when colour.backend or depth.backend is \"replay\"");
}

// What bindSettings() binds, and whether a file that says it ends with
// [end] (daemon.end_marker = true) lacks it: then it was cut short.
bool bindSettingsFindingCut(TomlSection &root, Settings &s)
{
	bool endMarker = false;
	root.table("daemon", [&](TomlSection &sec) {
		bindDaemon(sec, s.daemon);
		sec.boolean("end_marker", endMarker);
	});
	root.table("colour", [&](TomlSection &sec) { bindColour(sec, s.colour); });
	root.table("depth", [&](TomlSection &sec) { bindDepth(sec, s.depth); });
	root.table("pairing", [&](TomlSection &sec) { bindPairing(sec, s.pairing, s.colour.fps, s.depth.fps); });
	root.table("segmentation", [&](TomlSection &sec) { bindSegmentation(sec, s.segmentation); });
	root.table("mapping", [&](TomlSection &sec) { bindMapping(sec, s.mapping); });
	root.table("learning", [&](TomlSection &sec) { bindLearning(sec, s.learning); });
	root.table("siox", [&](TomlSection &sec) { bindSiox(sec, s.siox); });
	root.table("decision", [&](TomlSection &sec) { bindDecision(sec, s.decision); });
	root.table("composite", [&](TomlSection &sec) { bindComposite(sec, s.composite); });
	root.table("board", [&](TomlSection &sec) { bindBoard(sec, s.board); });
	root.table("output", [&](TomlSection &sec) {
		bindOutput(sec, s.output);
		bindV4l2Output(sec, s, s.output);
	});
	root.table("preview", [&](TomlSection &sec) { bindPreview(sec, s.preview); });
	root.table("leds", [&](TomlSection &sec) { bindLeds(sec, s.leds); });
	root.table("sim", [&](TomlSection &sec) { bindSim(sec, s.sim); });
	bool replayUsed = s.colour.backend == "replay" || s.depth.backend == "replay";
	root.table("replay", [&](TomlSection &sec) { bindReplay(sec, s.replay, replayUsed); });
	root.table("end", [](TomlSection &) {}); // a marker: no keys
	return endMarker && !root.has("end");
}

constexpr const char *kCutShort = "missing section [end]: the file is cut short (daemon.end_marker = true "
				  "says it ends with [end])";

} // namespace

void bindSettings(TomlSection &root, Settings &s)
{
	if (bindSettingsFindingCut(root, s))
		root.require(false, "end", kCutShort);
}

std::string findDefaultConfig()
{
	constexpr const char *kSystemConfig = "/etc/depthkey/depthkey.toml";
	struct stat st;
	auto exists = [&st](const std::string &path) { return stat(path.c_str(), &st) == 0; };
	if (exists(kSystemConfig))
		return kSystemConfig;
	char buf[4096];
	ssize_t n = readlink("/proc/self/exe", buf, sizeof(buf) - 1);
	if (n > 0) {
		std::string exe(buf, static_cast<size_t>(n));
		std::string dir = exe.substr(0, exe.rfind('/'));
		for (const char *up : { "/../../config/depthkey.toml", "/../../../config/depthkey.toml" })
			if (exists(dir + up))
				return dir + up;
	}
	return kSystemConfig;
}

ConfigResult parseConfig(std::string_view text, const std::string &sourceName)
{
	ConfigResult result;
	bool cut = false;
	TomlBindResult bound = bindToml(text, sourceName, [&](TomlSection &root) {
		cut = bindSettingsFindingCut(root, result.settings);
	});
	result.errors = std::move(bound.errors);
	// At the last line, where a file cut short stops (as the calibration
	// files report their missing [end]).
	if (cut)
		result.errors.push_back({ sourceName, lastLineOf(text), 1, "end", kCutShort });
	return result;
}

ConfigResult loadConfig(const std::string &path)
{
	std::string text, why;
	if (readTextFile(path, kMaxConfigFileBytes, text, why) < 0) {
		ConfigResult result;
		result.errors.push_back({ path, 0, 0, "", "cannot read config file: " + why });
		return result;
	}
	return parseConfig(text, path);
}

} // namespace depthkey
