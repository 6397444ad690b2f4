// depthkey-shmcat's command line: the options, their help text and a parser
// that range-checks every number before narrowing it (issue 31 point 15).
// Included by tools/shmcat.cpp only (a tool is one .cpp file).
#pragma once

#include <cctype>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace shmcat {

// Bounds of the command line, checked before any narrowing or duration
// arithmetic: a timeout above a year would overflow steady_clock's
// nanoseconds (issue 31), and more than 10^12 frames is a typo.
constexpr double kMaxTimeoutSec = 365.0 * 24 * 3600;
constexpr uint64_t kMaxFrames = 1000000000000ull;
constexpr uint32_t kMaxFps = 1000;
// Written when the rate cannot be measured (fewer than two frames).
constexpr uint32_t kFallbackFps = 25;

struct Options {
	std::string stream = "composite";
	std::string name;          // "" = /depthkey.<stream>
	uint64_t frames = 0;       // 0 = until interrupted
	double timeoutSec = 5.0;
	uint32_t fps = 0;          // 0 = measured
	bool yuv420 = false;
	std::string anchor;        // "" = none; else the file for the first frame's capture time
};

inline void usage(FILE *out)
{
	std::fprintf(out,
		     "usage: depthkey-shmcat [--stream composite|lecturer] [--name /obj]\n"
		     "                       [--frames N] [--timeout SEC] [--fps N]\n"
		     "                       [--yuv420 | --chroma 444|420] [--anchor FILE]\n"
		     "Writes YUV4MPEG2 (full-range BT.601) to stdout: C444, or C420jpeg with\n"
		     "--yuv420, for the composite; C444alpha for the lecturer layer.\n"
		     "  --frames N     stop after N frames (default 0: run until killed)\n"
		     "  --timeout SEC  fail when no new frame arrives for SEC s (default 5)\n"
		     "  --fps N        frame rate written to the y4m header, 1..%u (default:\n"
		     "                 measured: the frames the stream published over their\n"
		     "                 capture timestamps of the first two seconds, written as \n"
		     "                 N:1, 30000:1001 style or to 1/1000 fps; %u when fewer\n"
		     "                 than two frames come within 2.5 s)\n"
		     "  --yuv420       4:2:0 chroma (2x2 mean) for the composite, for H.264\n"
		     "                 players: ... | ffmpeg -i - -pix_fmt yuv420p out.mp4\n"
		     "  --chroma 444|420  the same choice spelt out (default 444)\n"
		     "  --anchor FILE  write the first written frame's capture time to FILE as\n"
		     "                 CLOCK_REALTIME seconds (what ffmpeg stamps ALSA and Pulse\n"
		     "                 audio with), for -itsoffset when muxing sound\n",
		     kMaxFps, kFallbackFps);
}

// Parses an unsigned decimal into [min, max] without narrowing first: a
// sign, trailing text or a value out of range is refused by name.
inline bool parseUnsigned(const std::string &option, const std::string &value, uint64_t min,
		   uint64_t max, uint64_t *out)
{
	errno = 0;
	char *end = nullptr;
	const unsigned long long parsed = std::strtoull(value.c_str(), &end, 10);
	if (value.empty() || !std::isdigit(static_cast<unsigned char>(value[0])) || *end != '\0' ||
	    errno == ERANGE || parsed < min || parsed > max) {
		std::fprintf(stderr, "depthkey-shmcat: bad value for %s: '%s' (expected a whole "
			     "number %llu..%llu)\n", option.c_str(), value.c_str(),
			     static_cast<unsigned long long>(min), static_cast<unsigned long long>(max));
		return false;
	}
	*out = parsed;
	return true;
}

// Returns 0, or 2 for a usage error (message printed).
inline int parseOptions(int argc, char **argv, Options *opts)
{
	for (int i = 1; i < argc; i++) {
		std::string arg = argv[i];
		std::string value;
		size_t eq = arg.find('=');
		if (arg == "--help" || arg == "-h") {
			usage(stdout);
			std::exit(0);
		}
		if (arg == "--yuv420") {
			opts->yuv420 = true;
			continue;
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

		uint64_t number = 0;
		if (arg == "--stream" && (value == "composite" || value == "lecturer")) {
			opts->stream = value;
		} else if (arg == "--name" && !value.empty() && value[0] == '/') {
			opts->name = value;
		} else if (arg == "--anchor" && !value.empty()) {
			opts->anchor = value;
		} else if (arg == "--chroma" && (value == "444" || value == "420")) {
			opts->yuv420 = value == "420";
		} else if (arg == "--frames") {
			if (!parseUnsigned(arg, value, 0, kMaxFrames, &number))
				return 2;
			opts->frames = number;
		} else if (arg == "--fps") {
			if (!parseUnsigned(arg, value, 1, kMaxFps, &number))
				return 2;
			opts->fps = static_cast<uint32_t>(number); // <= kMaxFps
		} else if (arg == "--timeout") {
			char *end = nullptr;
			opts->timeoutSec = std::strtod(value.c_str(), &end);
			if (value.empty() || *end != '\0' || !(opts->timeoutSec > 0) ||
			    !(opts->timeoutSec <= kMaxTimeoutSec)) {
				std::fprintf(stderr, "depthkey-shmcat: bad value for --timeout: '%s' "
					     "(expected seconds, more than 0 and at most %.0f)\n",
					     value.c_str(), kMaxTimeoutSec);
				return 2;
			}
		} else {
			std::fprintf(stderr, "depthkey-shmcat: bad option %s %s\n", arg.c_str(),
				     value.c_str());
			usage(stderr);
			return 2;
		}
	}
	if (opts->name.empty())
		opts->name = "/depthkey." + opts->stream;
	return 0;
}

} // namespace shmcat
