// The depthkey config schema, one function per section, and file loading.
#include "config/config_loader.hpp"

#include <cerrno>
#include <cstring>
#include <limits>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "config/toml_binder.hpp"

namespace depthkey {

namespace {

// The values each enumeration accepts. Adding a backend ("sr2", "v4l2",
// "replay") is one edit here, once the daemon can build it.
constexpr std::string_view kLogLevels[] = { "error", "warning", "info", "debug" };
constexpr std::string_view kColourBackends[] = { "sim", "replay" };
constexpr std::string_view kDepthBackends[] = { "sim", "replay" };
constexpr std::string_view kLedBackends[] = { "none" };

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

// The daemon runs from / under systemd, so a relative path would land
// somewhere nobody looks.
std::string checkOptionalAbsolutePath(std::string_view path)
{
	return path.empty() ? "" : checkAbsolutePath(path);
}

// POSIX shared memory names are "/name": one leading slash and no other.
std::string checkShmName(std::string_view name)
{
	if (name.size() < 2 || name[0] != '/' ||
	    name.find('/', 1) != std::string_view::npos || hasNul(name))
		return "must be \"/name\": a leading '/' and no other '/'";
	if (name.size() > 255)
		return "is longer than 255 characters";
	return "";
}

// "" (the daemon's own group) or a plain group name, as useradd accepts.
std::string checkGroupName(std::string_view group)
{
	if (group.empty())
		return "";
	bool plain = group.size() <= 32 && group[0] != '-' &&
		     group.find_first_not_of("abcdefghijklmnopqrstuvwxyz"
					     "ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_.-") ==
			     std::string_view::npos;
	return plain ? "" : "is not a group name";
}

void bindDaemon(TomlSection &sec, DaemonSettings &s)
{
	sec.string("log_level", s.logLevel, kLogLevels);
	sec.string("snapshot_dir", s.snapshotDir, checkOptionalAbsolutePath);
	sec.string("record_dir", s.recordDir, checkOptionalAbsolutePath);
	sec.integer("record_compression", s.recordCompression, 0, 9);
}

void bindColour(TomlSection &sec, ColourCameraSettings &s)
{
	sec.string("backend", s.backend, kColourBackends);
	sec.string("device", s.device, checkAbsolutePath);
	sec.integer("width", s.width, 16, 1920);
	sec.integer("height", s.height, 16, 1080);
	sec.integer("fps", s.fps, 1, 60);
}

void bindDepth(TomlSection &sec, DepthCameraSettings &s)
{
	sec.string("backend", s.backend, kDepthBackends);
	sec.integer("fps", s.fps, 1, 60);
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
}

void bindComposite(TomlSection &sec, CompositeSettings &s)
{
	sec.number("opacity", s.opacity, 0.0, 1.0);
	sec.colour("board_colour", s.boardColour);
}

void bindOutput(TomlSection &sec, OutputSettings &s)
{
	bool ok = sec.string("composite_name", s.compositeName, checkShmName);
	ok = sec.string("lecturer_name", s.lecturerName, checkShmName) && ok;
	sec.integer("slots", s.slots, 2, 8);
	sec.string("group", s.group, checkGroupName);

	// Both streams in one shared memory object would corrupt each other.
	if (ok)
		sec.require(s.compositeName != s.lecturerName,
			    sec.has("lecturer_name") ? "lecturer_name" : "composite_name",
			    "composite_name and lecturer_name must differ");
}

void bindLeds(TomlSection &sec, LedSettings &s)
{
	sec.string("backend", s.backend, kLedBackends);
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

} // namespace

void bindSettings(TomlSection &root, Settings &s)
{
	root.table("daemon", [&](TomlSection &sec) { bindDaemon(sec, s.daemon); });
	root.table("colour", [&](TomlSection &sec) { bindColour(sec, s.colour); });
	root.table("depth", [&](TomlSection &sec) { bindDepth(sec, s.depth); });
	root.table("segmentation", [&](TomlSection &sec) { bindSegmentation(sec, s.segmentation); });
	root.table("composite", [&](TomlSection &sec) { bindComposite(sec, s.composite); });
	root.table("output", [&](TomlSection &sec) { bindOutput(sec, s.output); });
	root.table("leds", [&](TomlSection &sec) { bindLeds(sec, s.leds); });
	root.table("sim", [&](TomlSection &sec) { bindSim(sec, s.sim); });
	bool replayUsed = s.colour.backend == "replay" || s.depth.backend == "replay";
	root.table("replay", [&](TomlSection &sec) { bindReplay(sec, s.replay, replayUsed); });
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
	TomlBindResult bound = bindToml(text, sourceName, [&](TomlSection &root) {
		bindSettings(root, result.settings);
	});
	result.errors = std::move(bound.errors);
	return result;
}

ConfigResult loadConfig(const std::string &path)
{
	ConfigResult result;
	auto fail = [&](const char *what, int err) {
		result.errors.push_back({ path, 0, 0, "",
					  std::string(what) + ": " + std::strerror(err) });
		return result;
	};

	// POSIX I/O rather than iostreams: the errno says why (ENOENT, EACCES,
	// EISDIR), which is what a technician needs to fix it.
	int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
	if (fd < 0)
		return fail("cannot open config file", errno);

	std::string text;
	char buf[4096];
	for (;;) {
		ssize_t n = ::read(fd, buf, sizeof(buf));
		if (n < 0 && errno == EINTR)
			continue;
		if (n < 0) {
			int err = errno;
			::close(fd);
			return fail("cannot read config file", err);
		}
		if (n == 0)
			break;
		text.append(buf, static_cast<size_t>(n));
	}
	::close(fd);

	return parseConfig(text, path);
}

} // namespace depthkey
