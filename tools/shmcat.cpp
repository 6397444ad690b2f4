// depthkey-shmcat: dumps a depthkeyd shared-memory stream as YUV4MPEG2 on
// stdout, e.g.  depthkey-shmcat --frames 100 | ffmpeg -i - out.mp4
//
// It is also the reference consumer of hal/depthkey_shm.h: it uses nothing but
// the C reader, re-opens when the writer restarts and writes nothing to the
// object but its presence heartbeats (every poll beats; the daemon's reader
// LED and STATUS count it). Without write access to the object it still
// reads, uncounted, and says so once.
//
// Output: RGB24 streams as "C444 XCOLORRANGE=FULL" (yuv444p, full-range
// BT.601 / JFIF, no chroma subsampling so colour edges of the key survive),
// RGBA32 streams as "C444alpha XCOLORRANGE=FULL" (yuva444p, straight alpha).
// The format follows the object's fourcc; --stream only picks the default
// name. Each frame number is emitted at most once; when the writer is faster
// than the consumer, intermediate frames are skipped.
#include "hal/depthkey_shm.h"

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

namespace {

struct Options {
	std::string stream = "composite";
	std::string name;          // "" = /depthkey.<stream>
	unsigned long frames = 0;  // 0 = until interrupted
	double timeoutSec = 5.0;
	int fps = 25;
};

using Clock = std::chrono::steady_clock;
constexpr auto kPollInterval = std::chrono::milliseconds(2);

void usage(FILE *out)
{
	std::fprintf(out,
		     "usage: depthkey-shmcat [--stream composite|lecturer] [--name /obj]\n"
		     "                       [--frames N] [--timeout SEC] [--fps N]\n"
		     "Writes YUV4MPEG2 (C444 or C444alpha, full-range BT.601) to stdout.\n"
		     "  --frames N     stop after N frames (default 0: run until killed)\n"
		     "  --timeout SEC  fail when no new frame arrives for SEC s (default 5)\n"
		     "  --fps N        frame rate written to the y4m header (default 25)\n");
}

// Returns 0, or 2 for a usage error (message printed).
int parseOptions(int argc, char **argv, Options *opts)
{
	for (int i = 1; i < argc; i++) {
		std::string arg = argv[i];
		std::string value;
		size_t eq = arg.find('=');
		if (arg == "--help" || arg == "-h") {
			usage(stdout);
			std::exit(0);
		}
		if (eq != std::string::npos) {
			value = arg.substr(eq + 1);
			arg.resize(eq);
		} else if (i + 1 < argc) {
			value = argv[++i];
		} else {
			std::fprintf(stderr, "depthkey-shmcat: %s needs a value\n", arg.c_str());
			return 2;
		}

		char *end = nullptr;
		if (arg == "--stream" && (value == "composite" || value == "lecturer")) {
			opts->stream = value;
		} else if (arg == "--name" && !value.empty() && value[0] == '/') {
			opts->name = value;
		} else if (arg == "--frames") {
			opts->frames = std::strtoul(value.c_str(), &end, 10);
		} else if (arg == "--timeout") {
			opts->timeoutSec = std::strtod(value.c_str(), &end);
			if (!(opts->timeoutSec > 0))
				end = nullptr;
		} else if (arg == "--fps") {
			opts->fps = static_cast<int>(std::strtol(value.c_str(), &end, 10));
			if (opts->fps < 1 || opts->fps > 1000)
				end = nullptr;
		} else {
			std::fprintf(stderr, "depthkey-shmcat: bad option %s %s\n", arg.c_str(),
				     value.c_str());
			usage(stderr);
			return 2;
		}
		if ((arg == "--frames" || arg == "--timeout" || arg == "--fps") &&
		    (!end || *end != '\0' || value.empty())) {
			std::fprintf(stderr, "depthkey-shmcat: bad value for %s: '%s'\n",
				     arg.c_str(), value.c_str());
			return 2;
		}
	}
	if (opts->name.empty())
		opts->name = "/depthkey." + opts->stream;
	return 0;
}

// Full-range BT.601 (JFIF), coefficients scaled by 2^16 and rounded so that
// each row sums exactly: Y = 0.299 R + 0.587 G + 0.114 B -> 19595, 38470,
// 7471 (sum 65536, so white is exactly 255); Cb = -0.168736 R - 0.331264 G +
// 0.5 B -> -11058, -21710, 32768 (sum 0, so greys have Cb = 128 exactly);
// Cr = 0.5 R - 0.418688 G - 0.081312 B -> 32768, -27439, -5329 (sum 0).
// The +32768 rounds to nearest; Cb/Cr can reach 256 for pure blue/red.
inline uint8_t clampByte(int v)
{
	return static_cast<uint8_t>(v > 255 ? 255 : v);
}

void convertRow(const uint8_t *src, int width, int bpp, uint8_t *y, uint8_t *u, uint8_t *v,
		uint8_t *a)
{
	constexpr int kHalf = 1 << 15;
	constexpr int kChromaOffset = 128 << 16;
	for (int x = 0; x < width; x++, src += bpp) {
		const int r = src[0], g = src[1], b = src[2];
		y[x] = static_cast<uint8_t>((19595 * r + 38470 * g + 7471 * b + kHalf) >> 16);
		u[x] = clampByte((-11058 * r - 21710 * g + 32768 * b + kChromaOffset + kHalf) >> 16);
		v[x] = clampByte((32768 * r - 27439 * g - 5329 * b + kChromaOffset + kHalf) >> 16);
		if (a)
			a[x] = src[3];
	}
}

class ShmCat
{
public:
	explicit ShmCat(const Options &opts) : opts_(opts) {}
	~ShmCat() { dk_shm_close(&reader_); }
	int run();

private:
	int openReader(bool first, Clock::time_point deadline);
	int emit(const dk_shm_frame_info &info);

	const Options &opts_;
	dk_shm_reader reader_{};
	uint32_t width_ = 0, height_ = 0, fourcc_ = 0;
	std::vector<uint8_t> frame_;
	std::vector<uint8_t> out_;
};

// Retries while the writer is (re)creating the object. A missing object is
// fatal at start-up, but only a timeout after a restart: the new writer may
// be about to create it.
int ShmCat::openReader(bool first, Clock::time_point deadline)
{
	const char *name = opts_.name.c_str();
	for (;;) {
		int ret = dk_shm_open(name, &reader_);
		if (ret == 0)
			return 0;
		if (ret == -ENOENT && first) {
			std::fprintf(stderr, "depthkey-shmcat: %s does not exist (is depthkeyd running?)\n",
				     name);
			return ret;
		}
		if (ret == -EPROTO) {
			std::fprintf(stderr, "depthkey-shmcat: %s is not a depthkey frame ring of "
				     "version %u (or is truncated)\n", name, DK_SHM_VERSION);
			return ret;
		}
		if (ret != -EAGAIN && ret != -ENOENT) {
			std::fprintf(stderr, "depthkey-shmcat: cannot open %s: %s\n", name,
				     std::strerror(-ret));
			return ret;
		}
		if (Clock::now() >= deadline) {
			std::fprintf(stderr, "depthkey-shmcat: timeout: %s not ready after %.1f s\n",
				     name, opts_.timeoutSec);
			return -ETIMEDOUT;
		}
		std::this_thread::sleep_for(kPollInterval);
	}
}

int ShmCat::emit(const dk_shm_frame_info &info)
{
	const int bpp = static_cast<int>(dk_shm_bytes_per_pixel(fourcc_));
	const size_t plane = static_cast<size_t>(width_) * height_;
	const size_t planes = bpp == 4 ? 4 : 3;
	static const char kFrame[] = "FRAME\n";

	out_.resize(sizeof(kFrame) - 1 + planes * plane);
	std::memcpy(out_.data(), kFrame, sizeof(kFrame) - 1);
	uint8_t *y = out_.data() + sizeof(kFrame) - 1;
	for (uint32_t row = 0; row < height_; row++) {
		const size_t off = static_cast<size_t>(row) * width_;
		convertRow(frame_.data() + static_cast<size_t>(row) * info.stride,
			   static_cast<int>(width_), bpp, y + off, y + plane + off,
			   y + 2 * plane + off, bpp == 4 ? y + 3 * plane + off : nullptr);
	}
	if (std::fwrite(out_.data(), 1, out_.size(), stdout) != out_.size() ||
	    std::fflush(stdout) != 0) {
		std::fprintf(stderr, "depthkey-shmcat: writing to stdout failed: %s\n",
			     std::strerror(errno));
		return -EIO;
	}
	return 0;
}

int ShmCat::run()
{
	const auto timeout = std::chrono::duration_cast<Clock::duration>(
		std::chrono::duration<double>(opts_.timeoutSec));
	auto lastNew = Clock::now();

	if (openReader(true, lastNew + timeout))
		return 1;
	if (reader_.presence_error)
		std::fprintf(stderr, "depthkey-shmcat: reading %s uncounted (no reader heartbeat: %s)\n",
			     opts_.name.c_str(), std::strerror(-reader_.presence_error));
	width_ = reader_.width;
	height_ = reader_.height;
	fourcc_ = reader_.fourcc;
	frame_.resize(reader_.frame_bytes);

	std::printf("YUV4MPEG2 W%u H%u F%d:1 Ip A1:1 %s XCOLORRANGE=FULL\n", width_, height_,
		    opts_.fps, fourcc_ == DK_SHM_FORMAT_RGBA32 ? "C444alpha" : "C444");

	uint64_t lastFrame = 0;
	unsigned long emitted = 0;
	while (opts_.frames == 0 || emitted < opts_.frames) {
		uint64_t latest = 0;
		int ret = dk_shm_latest(&reader_, &latest);
		if (ret == 0 && latest != 0 && latest != lastFrame) {
			dk_shm_frame_info info{};
			ret = dk_shm_read_latest(&reader_, frame_.data(), frame_.size(), &info);
			if (ret == 0 && info.frame != lastFrame) {
				if (emit(info))
					return 1;
				lastFrame = info.frame;
				lastNew = Clock::now();
				emitted++;
				continue;
			}
		}
		if (ret == -ESTALE) {
			// The writer restarted: frame numbers start again at 1.
			dk_shm_close(&reader_);
			if (openReader(false, lastNew + timeout))
				return 1;
			if (reader_.width != width_ || reader_.height != height_ ||
			    reader_.fourcc != fourcc_) {
				std::fprintf(stderr, "depthkey-shmcat: %s changed from %ux%u to %ux%u "
					     "or changed format; a y4m stream cannot follow, restart\n",
					     opts_.name.c_str(), width_, height_, reader_.width,
					     reader_.height);
				return 1;
			}
			lastFrame = 0;
			continue;
		}
		if (Clock::now() - lastNew >= timeout) {
			std::fprintf(stderr, "depthkey-shmcat: timeout: no new frame from %s for %.1f s "
				     "(writer %s)\n", opts_.name.c_str(), opts_.timeoutSec,
				     __atomic_load_n(&reader_.header->online, __ATOMIC_RELAXED) ?
				     "online" : "offline");
			return 1;
		}
		std::this_thread::sleep_for(kPollInterval);
	}
	return 0;
}

} // namespace

int main(int argc, char **argv)
{
	Options opts;
	int ret = parseOptions(argc, argv, &opts);
	if (ret)
		return ret;
	// Frames are written whole and flushed; a large buffer saves syscalls.
	static char buffer[1 << 16];
	std::setvbuf(stdout, buffer, _IOFBF, sizeof(buffer));

	ShmCat cat(opts);
	ret = cat.run();
	std::fflush(stdout);
	return ret;
}
