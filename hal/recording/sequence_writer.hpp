// Writes frames into a sequence folder (hal/recording/sequence_format.hpp).
// Synchronous: each call encodes PNGs; the daemon calls it from its
// recording thread (daemon/frame_recorder.hpp), the tools directly.
#pragma once

#include "algo/frames.hpp"
#include "hal/recording/sequence_format.hpp"

#include <cstdio>
#include <string>

namespace depthkey {

class SequenceWriter
{
public:
	// pngCompression: zlib level 0..9 (1 is fast and still about half the size).
	explicit SequenceWriter(int pngCompression = 1) : compression_(pngCompression) {}
	~SequenceWriter() { close(); }
	SequenceWriter(const SequenceWriter &) = delete;
	SequenceWriter &operator=(const SequenceWriter &) = delete;

	void setCompression(int pngCompression) { compression_ = pngCompression; }

	// Creates dir and its stream folders; an existing recording there is
	// appended to. Negative errno, with describeError() naming the path.
	int open(const std::string &dir);
	void close();

	int writeColour(const ColourFrame &frame);
	int writeDepth(const DepthFrame &frame);
	// Ground truth for the colour frame with this timestamp and sequence.
	int writeMask(const Gray8Image &mask, uint64_t timestampNs, uint64_t sequence);

	const std::string &describeError() const { return error_; }

private:
	template<typename Pixel>
	int writeImage(recording::Stream stream, const Image<Pixel> &image, uint64_t timestampNs, uint64_t sequence);

	int compression_;
	std::string dir_;
	std::FILE *index_[recording::StreamCount] = {};
	std::string error_;
};

} // namespace depthkey
