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
	// appended to, never overwritten: frames are numbered on from the
	// highest file number already in each stream's folder (fileNumber()).
	// A folder holding frames of an earlier boot is left as it is: the
	// session goes into dir/boot-N (hal/recording/session_folder.hpp), which
	// folder() names; so is a folder of colour frames of another size than
	// colourWidth x colourHeight (when given), into dir/WxH. Negative errno,
	// with describeError() naming the path.
	int open(const std::string &dir, int colourWidth = 0, int colourHeight = 0);
	const std::string &folder() const { return dir_; }
	void close();

	int writeColour(const ColourFrame &frame); // and its truth, when it has one, into mask/
	int writeDepth(const DepthFrame &frame);
	// Ground truth for the colour frame with this timestamp and sequence.
	int writeMask(const Gray8Image &mask, uint64_t timestampNs, uint64_t sequence);

	const std::string &describeError() const { return error_; }

private:
	template<typename Pixel>
	int writeImage(recording::Stream stream, const Image<Pixel> &image, uint64_t timestampNs, uint64_t sequence);

	// The number a frame's file gets: the camera's sequence, shifted past
	// every file of its camera's streams on disk or written since open(). A
	// restart (of the daemon, or of a camera by a reload or a re-open)
	// starts sequences at 1 again, and its frames would otherwise overwrite
	// the first ones while the index listed both (issue 31). Gaps in the
	// sequence (dropped frames) stay gaps. A stream after its camera's
	// first (mask after rgb; amplitude, intensity after depth) gets the
	// number its frame got there.
	uint64_t fileNumber(recording::Stream stream, uint64_t sequence);
	int findHighestNumbers();

	int compression_;
	std::string dir_;
	uint64_t highest_[recording::StreamCount] = {}; // highest file number on disk or written
	uint64_t shift_[2] = {};                        // per camera: colour, depth
	std::FILE *index_[recording::StreamCount] = {};
	std::string error_;
};

} // namespace depthkey
