// depthkey-calibrate's recorded views are read by the one sequence reader
// (hal/recording/sequence_reader.hpp) with rgb, depth and amplitude
// required: the same hostile inputs are refused safely (issue 14, cases G
// and H), and each colour frame finds the depth frame taken with it.
#include "hal/recording/sequence_reader.hpp"
#include "tests/hostile_files.hpp"
#include "tests/huge_png.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sys/stat.h>

using namespace depthkey;
using depthkey::test::FifoWithWriter;
using depthkey::test::ScratchDir;

namespace {

constexpr std::initializer_list<recording::Stream> kCalibrationStreams = { recording::Rgb, recording::Depth,
									   recording::Amplitude };

} // namespace

TEST(CalibrationSequence, HugePngAndFifoIndexAreRefused)
{
	ScratchDir dir;
	{
		FifoWithWriter fifo(dir / "rgb.txt", "1.0 rgb/000000.png\n");
		ASSERT_TRUE(fifo.ok());
		SequenceReader reader;
		EXPECT_EQ(reader.open(dir.path(), kCalibrationStreams), -EINVAL);
		EXPECT_EQ(reader.describeError(), dir / "rgb.txt" + ": cannot read: not a regular file (a FIFO)");
	}
	unlink((dir / "rgb.txt").c_str());
	for (const char *stream : { "rgb", "depth", "amplitude" })
		std::ofstream(dir / (std::string(stream) + ".txt"))
			<< "1.0 " << stream << "/000000.png\n";
	mkdir((dir / "rgb").c_str(), 0755);
	ASSERT_TRUE(test::writeHugePng(dir / "rgb/000000.png", 20000, 20000));
	SequenceReader reader;
	ASSERT_EQ(reader.open(dir.path(), kCalibrationStreams), 0) << reader.describeError();
	ColourFrame colour;
	EXPECT_EQ(reader.readColour(0, colour), -EFBIG);
	EXPECT_EQ(reader.describeError(),
		  dir / "rgb/000000.png" + ": 20000x20000 pixels, larger than the 1920x1080 accepted");
}

TEST(CalibrationSequence, RequiredIndexMissingIsNamed)
{
	ScratchDir dir;
	std::ofstream(dir / "rgb.txt") << "1.0 rgb/000000.png\n";
	std::ofstream(dir / "depth.txt") << "1.0 depth/000000.png\n";
	SequenceReader optional;
	EXPECT_EQ(optional.open(dir.path()), 0) << optional.describeError();
	SequenceReader reader;
	EXPECT_EQ(reader.open(dir.path(), kCalibrationStreams), -ENOENT);
	EXPECT_EQ(reader.describeError().rfind(dir / "amplitude.txt" + ": cannot read: ", 0), 0u)
		<< reader.describeError();
}

TEST(CalibrationSequence, ColourFrameFindsTheDepthFrameNearestInTime)
{
	ScratchDir dir;
	std::ofstream(dir / "rgb.txt") << "0.0 rgb/1.png\n1.0 rgb/2.png\n1.5 rgb/3.png\n9.0 rgb/4.png\n";
	std::ofstream(dir / "depth.txt") << "0.0 depth/1.png\n1.0 depth/2.png\n2.0 depth/3.png\n";
	SequenceReader reader;
	ASSERT_EQ(reader.open(dir.path()), 0) << reader.describeError();
	EXPECT_EQ(reader.depthNearestColour(0), 0u); // recorded together: one timestamp
	EXPECT_EQ(reader.depthNearestColour(1), 1u);
	EXPECT_EQ(reader.depthNearestColour(2), 1u); // as near to 1.0 as to 2.0: the earlier
	EXPECT_EQ(reader.depthNearestColour(3), 2u); // after the last depth frame
}
