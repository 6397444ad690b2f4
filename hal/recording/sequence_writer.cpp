#include "hal/recording/sequence_writer.hpp"

#include "hal/image_file.hpp"
#include "hal/recording/session_folder.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <dirent.h>
#include <ctime>
#include <sys/stat.h>
#include <vector>

namespace depthkey {

using namespace recording;

namespace {

int makeDir(const std::string &path)
{
	if (mkdir(path.c_str(), 0755) < 0 && errno != EEXIST)
		return -errno;
	return 0;
}

// The camera whose frames a stream holds: 0 colour, 1 depth.
int cameraOf(Stream stream)
{
	return stream == Rgb || stream == Mask ? 0 : 1;
}

// The number in "000042.png", else 0 (not one of ours).
uint64_t numberOf(const char *name)
{
	uint64_t number = 0;
	const char *c = name;
	for (; *c >= '0' && *c <= '9' && c - name < 19; ++c)
		number = number * 10 + static_cast<uint64_t>(*c - '0');
	return c != name && std::strcmp(c, ".png") == 0 ? number : 0;
}

} // namespace

int SequenceWriter::open(const std::string &dir, int colourWidth, int colourHeight)
{
	close();
	dir_ = dir;
	int ret = makeDir(dir);
	if (ret < 0) {
		error_ = dir + ": cannot create folder: " + std::strerror(-ret);
		return ret;
	}
	timespec now{};
	clock_gettime(CLOCK_MONOTONIC, &now);
	dir_ = sessionFolder(dir, static_cast<uint64_t>(now.tv_sec) * 1000000000u + static_cast<uint64_t>(now.tv_nsec),
			     colourWidth, colourHeight);
	if (dir_ != dir && (ret = makeDir(dir_)) < 0) {
		error_ = dir_ + ": cannot create folder: " + std::strerror(-ret);
		return ret;
	}
	for (int s = 0; s < StreamCount; ++s) {
		std::string sub = dir_ + "/" + kStreams[s];
		if ((ret = makeDir(sub)) < 0) {
			error_ = sub + ": cannot create folder: " + std::strerror(-ret);
			return ret;
		}
	}
	return findHighestNumbers();
}

// The folders rather than the index files: a crash between a PNG and its
// index line leaves a file the index does not name, which must not be
// overwritten either. One readdir per stream at open (a long recording's
// tens of thousands of names take milliseconds).
int SequenceWriter::findHighestNumbers()
{
	for (int s = 0; s < StreamCount; ++s) {
		std::string sub = dir_ + "/" + kStreams[s];
		DIR *folder = opendir(sub.c_str());
		if (!folder) {
			int err = errno;
			error_ = sub + ": cannot list folder: " + std::strerror(err);
			return -err;
		}
		highest_[s] = 0;
		while (const dirent *entry = readdir(folder))
			highest_[s] = std::max(highest_[s], numberOf(entry->d_name));
		closedir(folder);
	}
	shift_[0] = shift_[1] = 0;
	return 0;
}

uint64_t SequenceWriter::fileNumber(Stream stream, uint64_t sequence)
{
	const int camera = cameraOf(stream);
	if (stream == Rgb || stream == Depth) {
		uint64_t highest = 0;
		for (int s = 0; s < StreamCount; ++s)
			if (cameraOf(static_cast<Stream>(s)) == camera)
				highest = std::max(highest, highest_[s]);
		if (shift_[camera] + sequence <= highest)
			shift_[camera] = highest + 1 - sequence;
	}
	return shift_[camera] + sequence;
}

void SequenceWriter::close()
{
	for (std::FILE *&f : index_)
		if (f) {
			std::fclose(f);
			f = nullptr;
		}
}

template<typename Pixel>
int SequenceWriter::writeImage(Stream stream, const Image<Pixel> &image, uint64_t timestampNs, uint64_t sequence)
{
	if (dir_.empty()) {
		error_ = "recording folder not open";
		return -EBADF;
	}
	const uint64_t number = fileNumber(stream, sequence);
	std::string name = frameFileName(stream, number);
	std::string path = dir_ + "/" + name;
	if (int ret = writePng(path, image, error_, compression_); ret < 0)
		return ret;
	highest_[stream] = std::max(highest_[stream], number);
	std::FILE *&index = index_[stream];
	if (!index) {
		std::string indexPath = dir_ + "/" + kStreams[stream] + ".txt";
		struct stat st;
		bool fresh = stat(indexPath.c_str(), &st) != 0 || st.st_size == 0;
		index = std::fopen(indexPath.c_str(), "ae");
		if (!index) {
			int err = errno;
			error_ = indexPath + ": cannot open: " + std::strerror(err);
			return -err;
		}
		if (fresh)
			std::fprintf(index, "# %s frames of a depthkey recording\n# timestamp filename\n",
				     kStreams[stream]);
	}
	// Line-buffered on purpose: a recording cut short by a crash keeps every
	// frame whose line was written.
	if (std::fprintf(index, "%s %s\n", formatTimestamp(timestampNs).c_str(), name.c_str()) < 0 ||
	    std::fflush(index) != 0) {
		int err = errno;
		error_ = dir_ + "/" + kStreams[stream] + ".txt: cannot write: " + std::strerror(err);
		return -err;
	}
	return 0;
}

int SequenceWriter::writeColour(const ColourFrame &frame)
{
	int ret = writeImage(Rgb, frame.rgb, frame.timestampNs, frame.sequence);
	// A simulated camera's truth goes beside it: a replay of the recording
	// is scored live as the simulator is (issue 29).
	if (ret >= 0 && !frame.truth.empty())
		ret = writeMask(frame.truth, frame.timestampNs, frame.sequence);
	return ret;
}

int SequenceWriter::writeDepth(const DepthFrame &frame)
{
	int ret = writeImage(Depth, frame.depthMm, frame.timestampNs, frame.sequence);
	if (ret >= 0 && !frame.amplitude.empty())
		ret = writeImage(Amplitude, frame.amplitude, frame.timestampNs, frame.sequence);
	if (ret >= 0 && !frame.intensity.empty())
		ret = writeImage(Intensity, frame.intensity, frame.timestampNs, frame.sequence);
	return ret;
}

int SequenceWriter::writeMask(const Gray8Image &mask, uint64_t timestampNs, uint64_t sequence)
{
	return writeImage(Mask, mask, timestampNs, sequence);
}

} // namespace depthkey
