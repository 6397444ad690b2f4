// A recorded sequence on disk, the format of the simulator/replay issue:
// DIR/rgb/, DIR/depth/ (16-bit PNG, millimetres), DIR/amplitude/ (16-bit
// PNG), and index files DIR/rgb.txt, depth.txt, amplitude.txt listing
// "timestamp file" per frame in order ('#' starts a comment), in the manner
// of the TUM RGB-D benchmark. Frame i of each index belongs together.
//
// Only what depthkey-calibrate needs: reading frame pairs in order and
// writing them (--record). The replay backend reads the same folders with
// hal/recording/sequence_reader.hpp; the classes have distinct names, since
// two classes of one name in one program break the one-definition rule
// (their inline members get merged: a double free in a test binary using
// both).
#pragma once

#include <string>
#include <vector>

#include "algo/frames.hpp"

namespace depthkey {

class SequenceFolderReader
{
public:
	// Reads the three index files. Returns 0 or a negative errno with error
	// naming the file (and line) at fault.
	int open(const std::string &dir, std::string &error);
	size_t frames() const { return rgb_.size(); }
	// Loads frame i of each stream. Returns 0 or a negative errno with error.
	int read(size_t index, ColourFrame &colour, DepthFrame &depth, std::string &error) const;

private:
	std::string dir_;
	std::vector<std::string> rgb_, depth_, amplitude_;
	std::vector<double> stamps_;
};

class SequenceFolderWriter
{
public:
	// Creates dir and its sub-folders (dir may exist, empty or not).
	int open(const std::string &dir, std::string &error);
	// Appends a frame pair taken at timestampS, and rewrites the indexes.
	int write(double timestampS, const ColourFrame &colour, const DepthFrame &depth, std::string &error);

private:
	std::string dir_;
	std::string rgbIndex_, depthIndex_, amplitudeIndex_;
	size_t count_ = 0;
};

} // namespace depthkey
