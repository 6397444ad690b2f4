// depthkey-hil-shm-watch: waits, in the HIL VM, until the daemon's shared
// memory shows a state, and says how long that took. Used to assert that
// frames keep flowing while a device is gone (flags say offline) and to time
// the recovery once it is back.
//
//   depthkey-hil-shm-watch [--name /depthkey.composite] --until MASK=VALUE
//                          [--count N] [--since UPTIME] [--timeout S]
//                          [--alpha-between MIN MAX]
//
// Succeeds (exit 0) when N consecutive new frames have (flags & MASK) == VALUE
// and prints the time from UPTIME (seconds of CLOCK_BOOTTIME as in
// /proc/uptime, default: when it started) to the first of them being seen,
// and that moment itself ("at T"): a watcher started before a device returns
// sees the first good frame at once, whenever the return is known.
// --alpha-between also requires the share of pixels with alpha > 0 in the
// last frame (RGBA streams) to lie in [MIN, MAX], and prints it: the keyed
// lecturer, neither nothing nor everything. Exit 1 on timeout or a share out
// of range, with what was seen.
#include "hal/depthkey_shm.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <string>
#include <thread>
#include <vector>

namespace {

double uptimeNow()
{
	timespec ts;
	clock_gettime(CLOCK_BOOTTIME, &ts);
	return static_cast<double>(ts.tv_sec) + ts.tv_nsec * 1e-9;
}

struct Options {
	std::string name = "/depthkey.composite";
	uint32_t mask = 0, value = 0;
	int count = 1;
	double since = -1, timeout = 10;
	bool alpha = false;
	double alphaMin = 0, alphaMax = 1;
};

bool parse(int argc, char **argv, Options &o)
{
	bool until = false;
	for (int i = 1; i < argc; i++) {
		std::string arg = argv[i];
		if (arg == "--alpha-between" && i + 2 < argc) {
			o.alpha = true;
			o.alphaMin = std::atof(argv[++i]);
			o.alphaMax = std::atof(argv[++i]);
			continue;
		}
		if (i + 1 >= argc)
			return false;
		const char *v = argv[++i];
		if (arg == "--name")
			o.name = v;
		else if (arg == "--count")
			o.count = std::atoi(v);
		else if (arg == "--since")
			o.since = std::atof(v);
		else if (arg == "--timeout")
			o.timeout = std::atof(v);
		else if (arg == "--until" && std::sscanf(v, "%i=%i", (int *)&o.mask, (int *)&o.value) == 2)
			until = true;
		else
			return false;
	}
	return until && o.count > 0;
}

double alphaShare(const std::vector<uint8_t> &pixels, const dk_shm_reader &r)
{
	if (r.fourcc != DK_SHM_FORMAT_RGBA32 || r.width == 0 || r.height == 0)
		return -1;
	size_t covered = 0;
	for (uint32_t y = 0; y < r.height; y++)
		for (uint32_t x = 0; x < r.width; x++)
			covered += pixels[y * r.stride + 4 * x + 3] > 0;
	return static_cast<double>(covered) / (static_cast<double>(r.width) * r.height);
}

} // namespace

int main(int argc, char **argv)
{
	Options o;
	if (!parse(argc, argv, o)) {
		std::fprintf(stderr, "usage: depthkey-hil-shm-watch [--name /obj] --until MASK=VALUE [--count N]\n"
				     "       [--since UPTIME] [--timeout S] [--alpha-between MIN MAX]\n");
		return 2;
	}
	const double start = uptimeNow();
	const double since = o.since >= 0 ? o.since : start;
	dk_shm_reader reader{};
	bool open = false;
	std::vector<uint8_t> pixels;
	uint64_t lastFrame = 0, seen = 0;
	uint32_t lastFlags = 0;
	int run = 0;
	double runStart = 0;
	while (uptimeNow() - start < o.timeout) {
		if (!open) {
			open = dk_shm_open(o.name.c_str(), &reader) == 0;
			if (!open) {
				std::this_thread::sleep_for(std::chrono::milliseconds(20));
				continue;
			}
			pixels.resize(reader.frame_bytes);
		}
		uint64_t latest = 0;
		if (dk_shm_latest(&reader, &latest) == -ESTALE) {
			dk_shm_close(&reader);
			open = false;
			continue;
		}
		if (latest == lastFrame) {
			std::this_thread::sleep_for(std::chrono::milliseconds(5));
			continue;
		}
		dk_shm_frame_info info{};
		if (dk_shm_read_latest(&reader, pixels.data(), pixels.size(), &info) != 0)
			continue;
		double now = uptimeNow();
		lastFrame = info.frame;
		lastFlags = info.flags;
		seen++;
		if ((info.flags & o.mask) != o.value) {
			run = 0;
			continue;
		}
		if (run++ == 0)
			runStart = now;
		if (run < o.count)
			continue;
		std::printf("shm-watch: %s flags&0x%x==0x%x after %.3f s at %.3f (frame %llu flags 0x%x, %llu frames seen)",
			    o.name.c_str(), o.mask, o.value, runStart - since, runStart, (unsigned long long)info.frame,
			    info.flags, (unsigned long long)seen);
		if (!o.alpha) {
			std::printf("\n");
			return 0;
		}
		double share = alphaShare(pixels, reader);
		bool inRange = share >= o.alphaMin && share <= o.alphaMax;
		std::printf(" alpha>0 on %.3f of the pixels%s\n", share, inRange ? "" : ", out of range");
		return inRange ? 0 : 1;
	}
	std::printf("shm-watch: %s timeout after %.1f s waiting for flags&0x%x==0x%x: %s, last frame %llu flags 0x%x, "
		    "%llu new frames seen\n",
		    o.name.c_str(), o.timeout, o.mask, o.value, open ? "open" : "never opened",
		    (unsigned long long)lastFrame, lastFlags, (unsigned long long)seen);
	return 1;
}
