// PNG through OpenCV's imgcodecs; the index files are plain text.
#include "hal/sequence_folder.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <sstream>
#include <sys/stat.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "config/atomic_file.hpp"
#include "config/frame_limits.hpp"
#include "config/text_file.hpp"
#include "hal/image_file.hpp"
#include "hal/image_file_reader.hpp"

namespace depthkey {

namespace {

int readIndex(const std::string &dir, const char *name, std::vector<std::string> &files,
	      std::vector<double> *stamps, std::string &error)
{
	std::string path = dir + "/" + name;
	std::string text, why;
	if (int ret = readTextFile(path, kMaxIndexFileBytes, text, why); ret < 0) {
		error = "cannot read " + path + ": " + why;
		return ret;
	}
	std::istringstream in(text);
	std::string line;
	for (int number = 1; std::getline(in, line); number++) {
		if (line.empty() || line[0] == '#')
			continue;
		std::istringstream fields(line);
		double stamp;
		std::string file;
		if (!(fields >> stamp >> file)) {
			error = path + ":" + std::to_string(number) + ": expected \"timestamp file\"";
			return -EINVAL;
		}
		files.push_back(dir + "/" + file);
		if (stamps)
			stamps->push_back(stamp);
	}
	return 0;
}

template<typename T>
void copyMat(const cv::Mat &m, Image<T> &out)
{
	out.resize(m.cols, m.rows);
	for (int y = 0; y < m.rows; y++)
		std::memcpy(out.row(y), m.ptr(y), sizeof(T) * static_cast<size_t>(m.cols));
}

constexpr ImageLimits kFrameLimits{ kMaxFrameWidth, kMaxFrameHeight };

int readGray16(const std::string &path, Gray16Image &out, std::string &error)
{
	cv::Mat m;
	if (int ret = decodeImageFile(path, kFrameLimits, cv::IMREAD_UNCHANGED, m, error); ret < 0)
		return ret;
	if (m.type() != CV_16UC1) {
		error = path + ": not a 16-bit grey PNG";
		return -EINVAL;
	}
	copyMat(m, out);
	return 0;
}

} // namespace

int SequenceFolderReader::open(const std::string &dir, std::string &error)
{
	dir_ = dir;
	rgb_.clear();
	depth_.clear();
	amplitude_.clear();
	stamps_.clear();
	if (int ret = readIndex(dir, "rgb.txt", rgb_, &stamps_, error); ret < 0)
		return ret;
	if (int ret = readIndex(dir, "depth.txt", depth_, nullptr, error); ret < 0)
		return ret;
	if (int ret = readIndex(dir, "amplitude.txt", amplitude_, nullptr, error); ret < 0)
		return ret;
	if (depth_.size() != rgb_.size() || amplitude_.size() != rgb_.size()) {
		error = dir + ": rgb.txt, depth.txt and amplitude.txt list " + std::to_string(rgb_.size()) +
			", " + std::to_string(depth_.size()) + " and " +
			std::to_string(amplitude_.size()) + " frames";
		return -EINVAL;
	}
	return 0;
}

int SequenceFolderReader::read(size_t index, ColourFrame &colour, DepthFrame &depth, std::string &error) const
{
	cv::Mat bgr;
	if (int ret = decodeImageFile(rgb_[index], kFrameLimits, cv::IMREAD_COLOR, bgr, error); ret < 0)
		return ret;
	cv::Mat rgb;
	cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
	copyMat(rgb, colour.rgb);
	if (int ret = readGray16(depth_[index], depth.depthMm, error); ret < 0)
		return ret;
	if (int ret = readGray16(amplitude_[index], depth.amplitude, error); ret < 0)
		return ret;
	if (depth.amplitude.width() != depth.depthMm.width() ||
	    depth.amplitude.height() != depth.depthMm.height()) {
		error = amplitude_[index] + ": not the size of " + depth_[index];
		return -EINVAL;
	}
	colour.sequence = depth.sequence = index;
	colour.timestampNs = depth.timestampNs = static_cast<uint64_t>(stamps_[index] * 1e9);
	return 0;
}

int SequenceFolderWriter::open(const std::string &dir, std::string &error)
{
	dir_ = dir;
	count_ = 0;
	rgbIndex_ = "# colour frames: timestamp file\n";
	depthIndex_ = "# depth frames (16-bit PNG, millimetres): timestamp file\n";
	amplitudeIndex_ = "# ToF amplitude frames (16-bit PNG): timestamp file\n";
	for (const std::string &sub : { dir, dir + "/rgb", dir + "/depth", dir + "/amplitude" }) {
		if (::mkdir(sub.c_str(), 0755) < 0 && errno != EEXIST) {
			int ret = -errno;
			error = "cannot create " + sub + ": " + std::strerror(errno);
			return ret;
		}
	}
	return 0;
}

int SequenceFolderWriter::write(double timestampS, const ColourFrame &colour, const DepthFrame &depth,
			  std::string &error)
{
	char name[32], stamp[32];
	std::snprintf(name, sizeof(name), "%06zu.png", count_);
	std::snprintf(stamp, sizeof(stamp), "%.6f ", timestampS);

	if (int ret = writePng(dir_ + "/rgb/" + name, colour.rgb, error); ret < 0)
		return ret;
	if (int ret = writePng(dir_ + "/depth/" + name, depth.depthMm, error); ret < 0)
		return ret;
	if (int ret = writePng(dir_ + "/amplitude/" + name, depth.amplitude, error); ret < 0)
		return ret;
	count_++;

	rgbIndex_ += stamp + std::string("rgb/") + name + "\n";
	depthIndex_ += stamp + std::string("depth/") + name + "\n";
	amplitudeIndex_ += stamp + std::string("amplitude/") + name + "\n";
	for (auto [file, text] : { std::pair{ "/rgb.txt", &rgbIndex_ }, { "/depth.txt", &depthIndex_ },
				   { "/amplitude.txt", &amplitudeIndex_ } })
		if (int ret = writeFileAtomically(dir_ + file, *text, error); ret < 0)
			return ret;
	return 0;
}

} // namespace depthkey
