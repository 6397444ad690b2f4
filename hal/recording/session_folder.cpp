#include "hal/recording/session_folder.hpp"

#include "hal/image_file_reader.hpp"
#include "hal/recording/sequence_format.hpp"

#include <algorithm>
#include <cstdio>
#include <sstream>
#include <sys/stat.h>

namespace depthkey {

using namespace recording;

namespace {

// An index line is "<seconds> <file>": its tail holds the latest, since the
// writer appends in time order. 4 KiB is many lines of ~40 bytes.
constexpr long kTailBytes = 4096;

// The latest timestamp an index lists, and the file on its last line.
uint64_t lastIndexEntry(const std::string &path, std::string *lastFile = nullptr)
{
	std::FILE *file = std::fopen(path.c_str(), "re");
	if (!file)
		return 0;
	std::string tail(kTailBytes, '\0');
	size_t got = 0;
	if (std::fseek(file, -kTailBytes, SEEK_END) != 0)
		std::rewind(file); // shorter than the tail: all of it
	got = std::fread(tail.data(), 1, tail.size(), file);
	std::fclose(file);
	tail.resize(got);

	uint64_t latest = 0;
	std::istringstream lines(tail);
	for (std::string line; std::getline(lines, line);) {
		uint64_t ns = 0;
		const size_t space = line.find(' ');
		const std::string stamp = line.substr(0, space);
		if (!line.empty() && line[0] != '#' && parseTimestamp(stamp, ns)) {
			latest = std::max(latest, ns);
			if (lastFile && space != std::string::npos)
				*lastFile = line.substr(space + 1);
		}
	}
	return latest;
}

// Whether dir's colour frames are width x height, going by the last one
// listed (the header alone); true when there is none or it cannot be read:
// nothing to keep apart.
bool colourSizeIs(const std::string &dir, int width, int height)
{
	std::string last;
	lastIndexEntry(dir + "/" + kStreams[Rgb] + ".txt", &last);
	if (last.empty())
		return true;
	unsigned char header[64];
	std::FILE *file = std::fopen((dir + "/" + last).c_str(), "re");
	if (!file)
		return true;
	const size_t got = std::fread(header, 1, sizeof(header), file);
	std::fclose(file);
	int w = 0, h = 0;
	return !imageHeaderSize(header, got, w, h) || (w == width && h == height);
}

bool exists(const std::string &path)
{
	struct stat st;
	return stat(path.c_str(), &st) == 0;
}

} // namespace

uint64_t lastRecordedNs(const std::string &dir)
{
	uint64_t latest = 0;
	for (const char *stream : kStreams)
		latest = std::max(latest, lastIndexEntry(dir + "/" + stream + ".txt"));
	return latest;
}

std::string sessionFolder(const std::string &dir, uint64_t nowNs, int colourWidth, int colourHeight)
{
	if (colourWidth > 0 && !colourSizeIs(dir, colourWidth, colourHeight))
		return sessionFolder(dir + "/" + std::to_string(colourWidth) + "x" + std::to_string(colourHeight), nowNs);
	if (lastRecordedNs(dir) <= nowNs)
		return dir;
	for (int boot = 2;; boot++) {
		std::string folder = dir + "/boot-" + std::to_string(boot);
		if (!exists(folder) || lastRecordedNs(folder) <= nowNs)
			return folder;
	}
}

} // namespace depthkey
