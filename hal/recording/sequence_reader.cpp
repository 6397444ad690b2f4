#include "hal/recording/sequence_reader.hpp"

#include "config/frame_limits.hpp"
#include "config/text_file.hpp"
#include "hal/image_file_reader.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <sstream>
#include <unistd.h>

namespace depthkey {

using namespace recording;

namespace {

// The sequence number in "rgb/000042.png", else 0.
uint64_t sequenceFromName(const std::string &file)
{
	size_t slash = file.rfind('/'), dot = file.rfind('.');
	size_t start = slash == std::string::npos ? 0 : slash + 1;
	if (dot == std::string::npos || dot <= start)
		return 0;
	uint64_t n = 0;
	for (size_t i = start; i < dot; ++i) {
		if (file[i] < '0' || file[i] > '9')
			return 0;
		n = n * 10 + static_cast<uint64_t>(file[i] - '0');
	}
	return n;
}

template<typename Pixel> struct PixelType;
template<> struct PixelType<Rgb8> { static constexpr int channels = 3, bits = 8; static constexpr const char *name = "8-bit RGB"; };
template<> struct PixelType<uint16_t> { static constexpr int channels = 1, bits = 16; static constexpr const char *name = "16-bit grey"; };
template<> struct PixelType<uint8_t> { static constexpr int channels = 1, bits = 8; static constexpr const char *name = "8-bit grey"; };

} // namespace

int parseSequenceIndex(std::string_view text, const std::string &path,
		       std::vector<SequenceEntry> &index, std::string &error)
{
	std::istringstream in{ std::string(text) };
	std::string line;
	int lineNumber = 0;
	while (std::getline(in, line)) {
		lineNumber++;
		if (line.empty() || line[0] == '#')
			continue;
		std::istringstream fields(line);
		std::string stamp, file;
		SequenceEntry entry;
		if (!(fields >> stamp >> file) || !parseTimestamp(stamp, entry.timestampNs)) {
			error = path + ":" + std::to_string(lineNumber) + ": expected \"<seconds> <file>\"";
			return -EINVAL;
		}
		if (!index.empty() && entry.timestampNs < index.back().timestampNs) {
			error = path + ":" + std::to_string(lineNumber) + ": timestamp goes backwards";
			return -EINVAL;
		}
		entry.file = file;
		entry.sequence = sequenceFromName(file);
		if (entry.sequence == 0)
			entry.sequence = index.size() + 1;
		index.push_back(entry);
	}
	return 0;
}

int SequenceReader::readIndex(Stream stream, bool required)
{
	std::string path = dir_ + "/" + kStreams[stream] + ".txt";
	std::string text, why;
	int ret = readTextFile(path, kMaxIndexFileBytes, text, why);
	if (ret == -ENOENT && !required)
		return 0;
	if (ret < 0) {
		error_ = path + ": cannot read: " + why;
		return ret;
	}
	return parseSequenceIndex(text, path, index_[stream], error_);
}

int SequenceReader::checkMatches(Stream stream, Stream owner)
{
	const auto &a = index_[stream], &b = index_[owner];
	if (a.empty())
		return 0;
	bool same = a.size() == b.size();
	for (size_t i = 0; same && i < a.size(); ++i)
		same = a[i].timestampNs == b[i].timestampNs;
	if (!same) {
		error_ = dir_ + "/" + kStreams[stream] + ".txt: does not list the same timestamps as " +
			 kStreams[owner] + ".txt";
		return -EINVAL;
	}
	return 0;
}

int SequenceReader::open(const std::string &dir, std::initializer_list<Stream> required)
{
	dir_ = dir;
	for (auto &index : index_)
		index.clear();
	int ret;
	for (int s = 0; s < StreamCount; ++s) {
		Stream stream = static_cast<Stream>(s);
		bool isRequired = std::find(required.begin(), required.end(), stream) != required.end();
		if ((ret = readIndex(stream, isRequired)) < 0)
			return ret;
	}
	if (colour().empty() && depth().empty()) {
		error_ = dir + ": no frames (rgb.txt and depth.txt missing or empty)";
		return -ENOENT;
	}
	if ((ret = checkMatches(Amplitude, Depth)) < 0 || (ret = checkMatches(Intensity, Depth)) < 0 ||
	    (ret = checkMatches(Mask, Rgb)) < 0)
		return ret;
	return 0;
}

size_t SequenceReader::depthNearestColour(size_t i) const
{
	uint64_t t = colour().at(i).timestampNs;
	const auto &frames = depth();
	auto later = std::lower_bound(frames.begin(), frames.end(), t,
				      [](const SequenceEntry &e, uint64_t ns) { return e.timestampNs < ns; });
	if (later == frames.end())
		return frames.size() - 1;
	if (later != frames.begin() && t - std::prev(later)->timestampNs <= later->timestampNs - t)
		--later;
	return static_cast<size_t>(later - frames.begin());
}

template<typename Pixel>
int SequenceReader::readImage(Stream stream, size_t i, Image<Pixel> &out)
{
	const auto &index = index_[stream];
	if (i >= index.size()) {
		error_ = dir_ + "/" + kStreams[stream] + ".txt: no frame " + std::to_string(i);
		return -ERANGE;
	}
	std::string path = dir_ + "/" + index[i].file;
	// Bounded by the largest frame the config allows: a PNG claiming
	// 20000x20000 pixels is refused before anything is allocated for it.
	if (int ret = decodeImageFile(path, { kMaxFrameWidth, kMaxFrameHeight }, decoded_, error_); ret < 0)
		return ret;
	if (decoded_.channels != PixelType<Pixel>::channels || decoded_.bitDepth != PixelType<Pixel>::bits) {
		error_ = path + ": is not " + PixelType<Pixel>::name;
		return -EINVAL;
	}
	// The decoder gives RGB in RGB order and 16-bit samples in host order:
	// the layout of Image<Pixel> already.
	out.resize(decoded_.width, decoded_.height);
	std::memcpy(out.data(), decoded_.pixels.data(), sizeof(Pixel) * out.size());
	return 0;
}

int SequenceReader::readColour(size_t i, ColourFrame &out)
{
	int ret = readImage(Rgb, i, out.rgb);
	if (ret < 0)
		return ret;
	out.timestampNs = colour()[i].timestampNs;
	out.sequence = colour()[i].sequence;
	return 0;
}

int SequenceReader::readDepth(size_t i, DepthFrame &out)
{
	int ret = readImage(Depth, i, out.depthMm);
	if (ret < 0)
		return ret;
	for (auto [stream, image] : { std::pair{ Amplitude, &out.amplitude }, std::pair{ Intensity, &out.intensity } }) {
		if (!index_[stream].empty()) {
			if ((ret = readImage(stream, i, *image)) < 0)
				return ret;
			if (image->width() != out.depthMm.width() || image->height() != out.depthMm.height()) {
				error_ = dir_ + "/" + index_[stream][i].file + ": size differs from the depth image";
				return -EINVAL;
			}
		} else { // zeros in the frame's own storage: no allocation a frame
			image->resize(out.depthMm.width(), out.depthMm.height());
			std::fill(image->data(), image->data() + image->size(), uint16_t{ 0 });
		}
	}
	out.timestampNs = depth()[i].timestampNs;
	out.sequence = depth()[i].sequence;
	return 0;
}

int SequenceReader::readMask(size_t i, Gray8Image &out)
{
	return readImage(Mask, i, out);
}

} // namespace depthkey
