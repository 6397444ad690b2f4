// Reads a sequence folder (hal/recording/sequence_format.hpp): the index
// files at open(), the images on demand. Every problem is an error naming
// the file (and line) it is in; nothing throws.
#pragma once

#include "algo/frames.hpp"
#include "hal/png_codec.hpp"
#include "hal/recording/sequence_format.hpp"

#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

namespace depthkey {

struct SequenceEntry {
	uint64_t timestampNs = 0;
	uint64_t sequence = 0;  // from the file name, else the line's position
	std::string file;       // relative to the folder
};

// One index file's text (path names it in errors), appended to index.
// Pure, for the reader and its fuzzer (tests/fuzz/). Negative errno.
int parseSequenceIndex(std::string_view text, const std::string &path,
		       std::vector<SequenceEntry> &index, std::string &error);

class SequenceReader
{
public:
	// Needs rgb.txt or depth.txt (or both), and every index in required
	// (depthkey-calibrate needs rgb, depth and amplitude); amplitude,
	// intensity and mask indices are otherwise optional but, when there,
	// must list the same timestamps as the stream they belong to. Negative
	// errno; describeError() says why.
	int open(const std::string &dir, std::initializer_list<recording::Stream> required = {});

	const std::vector<SequenceEntry> &colour() const { return index_[recording::Rgb]; }
	const std::vector<SequenceEntry> &depth() const { return index_[recording::Depth]; }
	bool hasMask() const { return !index_[recording::Mask].empty(); }
	// The depth frame taken nearest in time to colour frame i (the earlier
	// of two as near); a colour and a depth frame recorded together have one
	// timestamp. Needs both streams.
	size_t depthNearestColour(size_t i) const;

	int readColour(size_t i, ColourFrame &out);
	int readDepth(size_t i, DepthFrame &out);   // amplitude/intensity zero if not recorded
	int readMask(size_t i, Gray8Image &out);    // for colour frame i

	const std::string &describeError() const { return error_; }
	const std::string &dir() const { return dir_; }

private:
	int readIndex(recording::Stream stream, bool required);
	int checkMatches(recording::Stream stream, recording::Stream owner);
	template<typename Pixel>
	int readImage(recording::Stream stream, size_t i, Image<Pixel> &out);

	std::string dir_;
	std::vector<SequenceEntry> index_[recording::StreamCount];
	std::string error_;
	DecodedImage decoded_; // reused: a replay of equally sized frames decodes without allocating
};

} // namespace depthkey
