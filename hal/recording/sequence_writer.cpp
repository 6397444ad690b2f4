#include "hal/recording/sequence_writer.hpp"

#include "hal/image_file.hpp"

#include <cerrno>
#include <cstring>
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

} // namespace

int SequenceWriter::open(const std::string &dir)
{
	close();
	dir_ = dir;
	int ret = makeDir(dir);
	if (ret < 0) {
		error_ = dir + ": cannot create folder: " + std::strerror(-ret);
		return ret;
	}
	for (int s = 0; s < StreamCount; ++s) {
		std::string sub = dir + "/" + kStreams[s];
		if ((ret = makeDir(sub)) < 0) {
			error_ = sub + ": cannot create folder: " + std::strerror(-ret);
			return ret;
		}
	}
	return 0;
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
	std::string name = frameFileName(stream, sequence);
	std::string path = dir_ + "/" + name;
	if (int ret = writePng(path, image, error_, compression_); ret < 0)
		return ret;
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
	return writeImage(Rgb, frame.rgb, frame.timestampNs, frame.sequence);
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
