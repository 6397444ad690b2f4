// depthkeyd: captures the colour and depth cameras, keys the lecturer out and
// publishes the composite and the lecturer layer to shared memory.
#include "config/config_loader.hpp"
#include "daemon/setup_report.hpp"
#include "daemon/daemon.hpp"
#include "daemon/log.hpp"
#include "daemon/version.hpp"

#include <cstdio>
#include <cstring>
#include <malloc.h>
#include <string>
#include <sys/stat.h>
#include <unistd.h>

using namespace depthkey;

namespace {

void usage(FILE *out)
{
	std::fprintf(out,
		     "usage: depthkeyd [--config FILE] [--snapshot-dir DIR] [--record DIR] [--preview DIR]\n"
		     "       depthkeyd --check-config FILE\n"
		     "       depthkeyd --version\n"
		     "\n"
		     "Without --config: %s, or config/depthkey.toml of the source tree\n"
		     "when run from build/bin/. Signals: SIGHUP re-reads the config,\n"
		     "SIGUSR1 writes stage snapshots, SIGTERM/SIGINT stop.\n"
		     "--record DIR records the camera frames (format: docs/sequences.md);\n"
		     "--preview DIR writes stage images of the first few keyed frames.\n",
		     "/etc/depthkey/depthkey.toml");
}

int checkConfig(const std::string &path)
{
	ConfigResult result = loadConfig(path);
	for (const ConfigError &e : result.errors)
		std::fprintf(stderr, "%s\n", e.toString().c_str());
	if (!result.ok())
		return 1;
	const Settings &settings = result.settings;
	std::printf("%s: ok\n%s", path.c_str(),
		    describeSetup(setupReport(settings, path, calibrationFromFiles(settings))).c_str());
	return 0;
}

} // namespace

int main(int argc, char **argv)
{
	// Blocks of 128 KiB and more (frames, stage buffers) come from and go
	// back to the kernel. glibc's default raises this threshold to the
	// largest block freed so far (the board source's first picture, 6 MB
	// at 1920x1080), after which frames freed on reconfiguration or after a
	// NO SIGNAL spell stay resident on the heap: 1.7 MB at 640x480
	// (issue 15). The keying allocates two such blocks a frame, the band's
	// minimum-cut graph (algo/band_graph_cut.hpp: OpenCV's GCGraph cannot
	// be reset), a few MB mapped and unmapped again: it costs no CPU time
	// measurably (BM_PipelineFrameLecture 34.6 / 35.7 ms with this
	// threshold against 33.8 / 35.7 ms with glibc's own, two runs), but
	// VmRSS sampled during a keying counts it. The preview thread's
	// pictures (while a client watches) are an mmap each.
	mallopt(M_MMAP_THRESHOLD, 128 * 1024);
	std::string configPath;
	CommandLineOverrides overrides;
	for (int i = 1; i < argc; ++i) {
		std::string arg = argv[i];
		if (arg == "--version") {
			std::printf("depthkeyd %s\n", DEPTHKEY_VERSION);
			return 0;
		} else if (arg == "--help" || arg == "-h") {
			usage(stdout);
			return 0;
		} else if (arg == "--check-config" && i + 1 < argc) {
			return checkConfig(argv[++i]);
		} else if (arg == "--config" && i + 1 < argc) {
			configPath = argv[++i];
		} else if (arg == "--snapshot-dir" && i + 1 < argc) {
			overrides.snapshotDir = argv[++i];
		} else if (arg == "--record" && i + 1 < argc) {
			overrides.recordDir = argv[++i];
		} else if (arg == "--preview" && i + 1 < argc) {
			overrides.previewDir = argv[++i];
		} else {
			std::fprintf(stderr, "depthkeyd: unknown or incomplete argument '%s'\n", arg.c_str());
			usage(stderr);
			return 2;
		}
	}
	if (configPath.empty())
		configPath = findDefaultConfig();

	ConfigResult config = loadConfig(configPath);
	if (!config.ok()) {
		for (const ConfigError &e : config.errors)
			logger().error("config: " + e.toString(), { { "CONFIG_FILE", e.file } });
		return 1;
	}

	Daemon daemon(configPath, overrides);
	int ret = daemon.start(config.settings);
	if (ret < 0) {
		logger().error("cannot start: " + (daemon.startError().empty() ? errnoText(ret) : daemon.startError()));
		return 1;
	}
	return daemon.run();
}
