#include "hal/recording/session_folder.hpp"

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

uint64_t lastIndexNs(const std::string &path)
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
		const std::string stamp = line.substr(0, line.find(' '));
		if (!line.empty() && line[0] != '#' && parseTimestamp(stamp, ns))
			latest = std::max(latest, ns);
	}
	return latest;
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
		latest = std::max(latest, lastIndexNs(dir + "/" + stream + ".txt"));
	return latest;
}

std::string sessionFolder(const std::string &dir, uint64_t nowNs)
{
	if (lastRecordedNs(dir) <= nowNs)
		return dir;
	for (int boot = 2;; boot++) {
		std::string folder = dir + "/boot-" + std::to_string(boot);
		if (!exists(folder) || lastRecordedNs(folder) <= nowNs)
			return folder;
	}
}

} // namespace depthkey
