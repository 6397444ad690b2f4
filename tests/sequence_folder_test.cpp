// depthkey-calibrate's sequence folders (hal/sequence_folder.hpp) read the
// same hostile inputs safely as the replay reader (issue 14, cases G and H).
#include "hal/sequence_folder.hpp"
#include "tests/hostile_files.hpp"
#include "tests/huge_png.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sys/stat.h>

using namespace depthkey;
using depthkey::test::FifoWithWriter;
using depthkey::test::ScratchDir;

TEST(CalibrationSequence, HugePngAndFifoIndexAreRefused)
{
	ScratchDir dir;
	std::string error;
	{
		FifoWithWriter fifo(dir / "rgb.txt", "1.0 rgb/000000.png\n");
		ASSERT_TRUE(fifo.ok());
		SequenceFolderReader reader;
		EXPECT_EQ(reader.open(dir.path(), error), -EINVAL);
		EXPECT_EQ(error, "cannot read " + dir / "rgb.txt" + ": not a regular file (a FIFO)");
	}
	unlink((dir / "rgb.txt").c_str());
	for (const char *stream : { "rgb", "depth", "amplitude" })
		std::ofstream(dir / (std::string(stream) + ".txt"))
			<< "1.0 " << stream << "/000000.png\n";
	mkdir((dir / "rgb").c_str(), 0755);
	ASSERT_TRUE(test::writeHugePng(dir / "rgb/000000.png", 20000, 20000));
	SequenceFolderReader reader;
	ASSERT_EQ(reader.open(dir.path(), error), 0) << error;
	ColourFrame colour;
	DepthFrame depth;
	EXPECT_EQ(reader.read(0, colour, depth, error), -EFBIG);
	EXPECT_EQ(error, dir / "rgb/000000.png" + ": 20000x20000 pixels, larger than the 1920x1080 accepted");
}
