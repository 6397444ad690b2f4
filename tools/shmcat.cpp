// depthkey-shmcat: dumps a depthkeyd shared-memory stream as YUV4MPEG2 on
// stdout, e.g.  depthkey-shmcat --frames 250 --yuv420 | ffmpeg -y -i - -pix_fmt yuv420p out.mp4
//
// It is also the reference consumer of hal/depthkey_shm.h: it uses nothing but
// the C reader, re-opens when the writer restarts and writes nothing to the
// object but its presence heartbeats (every poll beats; the daemon's reader
// LED and STATUS count it). Without write access to the object it still
// reads, uncounted, and says so once.
//
// Output: RGB24 streams as "C444 XCOLORRANGE=FULL" (yuv444p, full-range
// BT.601 / JFIF, no chroma subsampling so colour edges of the key survive) or,
// with --yuv420, "C420jpeg XCOLORRANGE=FULL" (yuv420p, what H.264 players and
// phones accept); RGBA32 streams as "C444alpha XCOLORRANGE=FULL" (yuva444p,
// straight alpha). The format follows the object's fourcc; --stream only
// picks the default name. Each frame number is emitted at most once; when the
// writer is faster than the consumer, intermediate frames are skipped.
//
// The header's rate is the rate the stream really delivers (issue 29): the
// published frame numbers over the capture timestamps of the first two seconds (a line fitted through them),
// so skipped frames do not lower it and a busy daemon's 14 fps is not
// written as 25. --fps overrides.
//
// The recording keeps time (issue 29 point 5): a player assumes that rate,
// so every slot of it in capture time, counted from the first frame's,
// gets one frame. Where the capture times skip slots (frames this reader
// was too slow for, the daemon's DK_SHM_FLAG_REPEATED copies it read past,
// or frames the daemon never published) the previous frame is written
// again, up to --timeout of them; a frame whose slot is taken (a stream
// faster than the header) is left out.
// At the end one line on stderr says how many frames cover how much
// capture time.
//
// Sound (docs/recording.md): ffmpeg stamps ALSA and PulseAudio/PipeWire
// audio with CLOCK_REALTIME; the header's capture times are
// CLOCK_MONOTONIC. --anchor FILE writes the first written frame's capture
// time converted to CLOCK_REALTIME (seconds), once, so that the video can be
// placed against audio recorded with -copyts (-itsoffset).
#include "algo/y4m_rows.hpp"
#include "hal/depthkey_shm.h"
#include "hal/shm_header_fault.hpp"
#include "tools/shmcat_options.hpp"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#include <time.h>
#include <vector>

using namespace depthkey;
using namespace shmcat;

namespace {

using Clock = std::chrono::steady_clock;
constexpr auto kPollInterval = std::chrono::milliseconds(2);
// The rate is measured over this much capture time or this many frame
// intervals, whichever comes first, and given up after kMeasureWall of wall
// time (a stalled stream then gets the fallback).
constexpr uint64_t kMeasureSpanNs = 2000000000ull;
constexpr uint64_t kMeasureFrames = 50;
constexpr auto kMeasureWall = std::chrono::milliseconds(2500);

class ShmCat
{
public:
	explicit ShmCat(const Options &opts) : opts_(opts) {}
	~ShmCat() { dk_shm_close(&reader_); }
	int run();

private:
	int openReader(bool first, Clock::time_point deadline);
	int takeGeometry();
	bool writeHeader(FrameRate rate);
	FrameRate measuredRate() const;
	// The frame in frame_ converted and written; convert() alone fills out_.
	void convert();
	int writeOut();
	int emit()
	{
		convert();
		return writeOut();
	}
	// Before a frame captured at ns, with `written` frames out: writes the
	// frame in out_ again for each slot of the header's rate since the
	// first frame that has none yet, up to `room` of them. Returns how
	// many, -1 when writing failed, or -2 when the frame's slot is taken
	// (the stream runs faster than the header says): it is left out.
	int64_t fillSlots(uint64_t ns, uint64_t written, uint64_t room);
	// --anchor: the first frame's capture time (CLOCK_MONOTONIC ns) as
	// CLOCK_REALTIME seconds into the file, and a line on stderr.
	int writeAnchor(uint64_t monotonicNs) const;

	const Options &opts_;
	dk_shm_reader reader_{};
	uint32_t width_ = 0, height_ = 0, stride_ = 0, fourcc_ = 0;
	int bpp_ = 0;
	bool yuv420_ = false;
	std::vector<uint8_t> frame_;
	std::vector<uint8_t> out_;
	std::vector<uint8_t> chromaRows_; // 4:2:0: two full-width rows of Cb and of Cr
	// Rate measurement: the first frame seen and the newest.
	dk_shm_frame_info first_{}, newest_{};
	// A line fitted through (frame number, capture time) of every frame
	// seen since first_ (least squares, relative to first_): a camera's
	// capture jitter at the two ends alone would move the rate by half a
	// percent over a second, and the recording's duration with it.
	struct RateFit {
		double n = 0, x = 0, y = 0, xx = 0, xy = 0;
		void add(double frame, double ns)
		{
			n += 1;
			x += frame;
			y += ns;
			xx += frame * frame;
			xy += frame * ns;
		}
		// Nanoseconds per frame number; 0 when it cannot be fitted.
		double slope() const
		{
			const double d = n * xx - x * x;
			return n >= 3 && d > 0 ? (n * xy - x * y) / d : 0;
		}
	} fit_;
	// Keeping time: the header's frame interval, the capture times of the
	// first and last frames written (0: none yet), the copies written.
	uint64_t intervalNs_ = 0, firstWrittenNs_ = 0, lastWrittenNs_ = 0, repeats_ = 0, dropped_ = 0;
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
			const std::string fault = shmObjectFault(name);
			std::fprintf(stderr, "depthkey-shmcat: %s is not a depthkey frame ring of "
				     "version %u: header %s\n", name, DK_SHM_VERSION,
				     fault.empty() ? "changed while read" : fault.c_str());
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

// The reader validated the geometry; it is checked again here against what
// this tool narrows it to (int widths, size_t buffers), so a change in the
// reader's rules cannot turn into an overrun here.
int ShmCat::takeGeometry()
{
	const uint32_t bpp = dk_shm_bytes_per_pixel(reader_.fourcc);
	if (bpp == 0 || reader_.width == 0 || reader_.width > DK_SHM_MAX_DIMENSION ||
	    reader_.height == 0 || reader_.height > DK_SHM_MAX_DIMENSION ||
	    reader_.stride < static_cast<uint64_t>(reader_.width) * bpp ||
	    reader_.frame_bytes != static_cast<uint64_t>(reader_.stride) * reader_.height ||
	    reader_.frame_bytes > SIZE_MAX / 2) {
		std::fprintf(stderr, "depthkey-shmcat: %s: header geometry out of range: width %u "
			     "height %u stride %u fourcc 0x%08x\n", opts_.name.c_str(), reader_.width,
			     reader_.height, reader_.stride, reader_.fourcc);
		return -EPROTO;
	}
	width_ = reader_.width;
	height_ = reader_.height;
	stride_ = reader_.stride;
	fourcc_ = reader_.fourcc;
	bpp_ = static_cast<int>(bpp);
	// Alpha has no 4:2:0 form in y4m: the lecturer layer stays 4:4:4.
	yuv420_ = opts_.yuv420 && bpp == 3;
	if (opts_.yuv420 && !yuv420_)
		std::fprintf(stderr, "depthkey-shmcat: %s has alpha: written as C444alpha, "
			     "--yuv420 applies to the composite only\n", opts_.name.c_str());
	frame_.resize(static_cast<size_t>(reader_.frame_bytes));
	const size_t plane = static_cast<size_t>(width_) * height_;
	const size_t chroma = yuv420_ ? static_cast<size_t>((width_ + 1) / 2) * ((height_ + 1) / 2)
				      : plane;
	static const char kFrame[] = "FRAME\n";
	out_.resize(sizeof(kFrame) - 1 + plane + 2 * chroma + (bpp == 4 ? plane : 0));
	std::memcpy(out_.data(), kFrame, sizeof(kFrame) - 1);
	chromaRows_.resize(yuv420_ ? 4 * static_cast<size_t>(width_) : 0);
	return 0;
}

bool ShmCat::writeHeader(FrameRate rate)
{
	const char *colour = fourcc_ == DK_SHM_FORMAT_RGBA32 ? "C444alpha"
			     : yuv420_			     ? "C420jpeg"
							     : "C444";
	intervalNs_ = static_cast<uint64_t>(rate.den) * 1000000000ull / rate.num;
	return std::printf("YUV4MPEG2 W%u H%u F%u:%u Ip A1:1 %s XCOLORRANGE=FULL\n", width_,
			   height_, rate.num, rate.den, colour) > 0;
}

// Published frames per second of capture time between the first and the
// newest frame seen: frame numbers count what the writer published, so
// frames this reader skipped still count, and a one-off late frame only
// shifts the end point.
FrameRate ShmCat::measuredRate() const
{
	const uint64_t frames = newest_.frame - first_.frame;
	const uint64_t spanNs = newest_.timestamp_ns - first_.timestamp_ns;
	if (first_.frame == 0 || frames == 0 || newest_.frame < first_.frame ||
	    newest_.timestamp_ns <= first_.timestamp_ns) {
		std::fprintf(stderr, "depthkey-shmcat: %s: too few frames to measure the rate, "
			     "writing %u fps (--fps sets it)\n", opts_.name.c_str(), kFallbackFps);
		return { kFallbackFps, 1 };
	}
	const double slopeNs = fit_.slope();
	const double fps = slopeNs > 0 ? 1e9 / slopeNs
				       : static_cast<double>(frames) * 1e9 / static_cast<double>(spanNs);
	if (!(fps >= kMinFrameRate && fps <= kMaxFrameRate)) {
		std::fprintf(stderr, "depthkey-shmcat: %s: measured %.3g fps from the capture "
			     "timestamps, not believed: writing %u fps (--fps sets it)\n",
			     opts_.name.c_str(), fps, kFallbackFps);
		return { kFallbackFps, 1 };
	}
	return y4mFrameRate(fps);
}

void ShmCat::convert()
{
	const size_t plane = static_cast<size_t>(width_) * height_;
	uint8_t *y = out_.data() + 6; // after "FRAME\n"
	const int width = static_cast<int>(width_); // <= DK_SHM_MAX_DIMENSION
	if (!yuv420_) {
		for (uint32_t row = 0; row < height_; row++) {
			const size_t off = static_cast<size_t>(row) * width_;
			rgbToYuv444Row_C(frame_.data() + static_cast<size_t>(row) * stride_, width,
					 bpp_, y + off, y + plane + off, y + 2 * plane + off,
					 bpp_ == 4 ? y + 3 * plane + off : nullptr);
		}
	} else {
		const size_t chromaWidth = (width_ + 1) / 2;
		uint8_t *u = y + plane;
		uint8_t *v = u + chromaWidth * ((height_ + 1) / 2);
		uint8_t *u0 = chromaRows_.data(), *u1 = u0 + width_;
		uint8_t *v0 = u1 + width_, *v1 = v0 + width_;
		for (uint32_t row = 0; row < height_; row += 2) {
			const uint8_t *src = frame_.data() + static_cast<size_t>(row) * stride_;
			rgbToYuv444Row_C(src, width, 3, y + static_cast<size_t>(row) * width_, u0, v0,
					 nullptr);
			const bool pair = row + 1 < height_;
			if (pair)
				rgbToYuv444Row_C(src + stride_, width, 3,
						 y + static_cast<size_t>(row + 1) * width_, u1, v1, nullptr);
			const size_t off = static_cast<size_t>(row / 2) * chromaWidth;
			subsampleChromaRow_C(u0, pair ? u1 : u0, width, u + off);
			subsampleChromaRow_C(v0, pair ? v1 : v0, width, v + off);
		}
	}
}

int64_t ShmCat::fillSlots(uint64_t ns, uint64_t written, uint64_t room)
{
	// Frames are counted from the first one's capture time, not from the
	// last one's: per-gap rounding of a jittery camera's times would add
	// or lose a frame now and then, and the duration would drift from the
	// capture time. An outage longer than --timeout, or times going back,
	// start the count again from here.
	// The first frame written starts the count too: nothing is in out_ yet
	// to repeat for the slots before it (a writer whose capture times
	// start near zero, as a test's, would otherwise get blank frames).
	const uint64_t maxGapNs = static_cast<uint64_t>(opts_.timeoutSec * 1e9);
	if (written == 0 || ns < lastWrittenNs_ || ns - lastWrittenNs_ > maxGapNs)
		firstWrittenNs_ = ns - std::min(ns, written * intervalNs_);
	const uint64_t due = (ns - firstWrittenNs_ + intervalNs_ / 2) / intervalNs_ + 1;
	if (due <= written) {
		dropped_++;
		return -2;
	}
	const uint64_t slots = std::min(due - written - 1, room);
	for (uint64_t i = 0; i < slots; i++)
		if (writeOut())
			return -1;
	repeats_ += slots;
	if (slots)
		lastWrittenNs_ = firstWrittenNs_ + (written + slots - 1) * intervalNs_;
	return static_cast<int64_t>(slots);
}

int ShmCat::writeAnchor(uint64_t monotonicNs) const
{
	if (opts_.anchor.empty())
		return 0;
	// The clocks' difference now: NTP slews CLOCK_REALTIME by parts per
	// million, nothing over the frame's few milliseconds of age.
	timespec mono{}, real{};
	clock_gettime(CLOCK_MONOTONIC, &mono);
	clock_gettime(CLOCK_REALTIME, &real);
	const double realS = double(real.tv_sec) + double(real.tv_nsec) * 1e-9 -
			     (double(mono.tv_sec) + double(mono.tv_nsec) * 1e-9 - double(monotonicNs) * 1e-9);
	FILE *file = std::fopen(opts_.anchor.c_str(), "w");
	const bool ok = file && std::fprintf(file, "%.6f\n", realS) > 0;
	if (file && std::fclose(file) != 0)
		file = nullptr;
	if (!ok || !file) {
		std::fprintf(stderr, "depthkey-shmcat: cannot write the anchor to %s: %s\n", opts_.anchor.c_str(),
			     std::strerror(errno));
		return -EIO;
	}
	std::fprintf(stderr, "depthkey-shmcat: first frame captured at %.6f s CLOCK_REALTIME (%llu ns CLOCK_MONOTONIC)\n",
		     realS, static_cast<unsigned long long>(monotonicNs));
	return 0;
}

int ShmCat::writeOut()
{
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

	if (openReader(true, lastNew + timeout) || takeGeometry())
		return 1;
	if (reader_.presence_error)
		std::fprintf(stderr, "depthkey-shmcat: reading %s uncounted (no reader heartbeat: %s)\n",
			     opts_.name.c_str(), std::strerror(-reader_.presence_error));

	// While measuring, frames are read for their timestamps; the newest is
	// held and becomes the first frame written after the header.
	bool measuring = opts_.fps == 0;
	bool held = false;
	Clock::time_point measureStart{};
	if (!measuring && !writeHeader({ opts_.fps, 1 }))
		return 1;

	uint64_t lastFrame = 0;
	uint64_t emitted = 0;
	while (opts_.frames == 0 || emitted < opts_.frames) {
		uint64_t latest = 0;
		int ret = dk_shm_latest(&reader_, &latest);
		if (ret == 0 && latest != 0 && latest != lastFrame) {
			dk_shm_frame_info info{};
			ret = dk_shm_read_latest(&reader_, frame_.data(), frame_.size(), &info);
			if (ret == 0 && info.frame != lastFrame) {
				lastFrame = info.frame;
				lastNew = Clock::now();
				if (!measuring) {
					const int64_t filled = fillSlots(info.timestamp_ns, emitted,
									 opts_.frames ? opts_.frames - emitted : UINT64_MAX);
					if (filled == -2)
						continue; // its slot is taken: time is kept
					if (filled < 0)
						return 1;
					emitted += static_cast<uint64_t>(filled);
					if (opts_.frames && emitted >= opts_.frames)
						break;
					if (emit())
						return 1;
					if (!emitted && writeAnchor(info.timestamp_ns))
						return 1;
					if (!firstWrittenNs_)
						firstWrittenNs_ = info.timestamp_ns;
					lastWrittenNs_ = info.timestamp_ns;
					emitted++;
					continue;
				}
				if (!held || info.frame <= first_.frame ||
				    info.timestamp_ns <= first_.timestamp_ns) {
					first_ = info; // the first, or numbers restarted: start again
					fit_ = {};
				}
				fit_.add(static_cast<double>(info.frame - first_.frame),
					 static_cast<double>(info.timestamp_ns - first_.timestamp_ns));
				// The wall-time limit is not restarted with the numbers: a
				// writer that restarts every few frames still gets a header.
				if (measureStart == Clock::time_point{})
					measureStart = lastNew;
				newest_ = info;
				held = true;
			}
		}
		if (measuring && held &&
		    (newest_.frame - first_.frame >= kMeasureFrames ||
		     newest_.timestamp_ns - first_.timestamp_ns >= kMeasureSpanNs ||
		     Clock::now() - measureStart >= std::min<Clock::duration>(kMeasureWall, timeout))) {
			measuring = false;
			if (!writeHeader(measuredRate()) || emit() || writeAnchor(newest_.timestamp_ns))
				return 1;
			firstWrittenNs_ = lastWrittenNs_ = newest_.timestamp_ns;
			emitted++;
			continue;
		}
		if (ret == -ESTALE) {
			// The writer restarted: frame numbers start again at 1.
			dk_shm_close(&reader_);
			if (openReader(false, lastNew + timeout))
				return 1;
			if (reader_.width != width_ || reader_.height != height_ ||
			    reader_.fourcc != fourcc_ || reader_.stride != stride_) {
				std::fprintf(stderr, "depthkey-shmcat: %s changed from %ux%u to %ux%u "
					     "or changed format; a y4m stream cannot follow, restart\n",
					     opts_.name.c_str(), width_, height_, reader_.width,
					     reader_.height);
				return 1;
			}
			lastFrame = 0;
			held = false; // the held frame stays in frame_, but numbers restart
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
	if (emitted > 0)
		std::fprintf(stderr, "depthkey-shmcat: %llu frames, %llu of them repeated for capture slots "
			     "the stream skipped, over %.3f s of capture time (%llu left out: their slot was taken)\n",
			     static_cast<unsigned long long>(emitted), static_cast<unsigned long long>(repeats_),
			     static_cast<double>(lastWrittenNs_ - firstWrittenNs_ + intervalNs_) / 1e9,
			     static_cast<unsigned long long>(dropped_));
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
