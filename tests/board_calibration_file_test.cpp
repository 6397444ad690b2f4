// The board calibration file: what the writer writes reads back bit for
// bit, and a cut, corrupt or impossible file is refused naming file, line,
// key and why.
#include "config/board_calibration_file.hpp"
#include "tests/sample_calibration.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

using namespace depthkey;

namespace {

BoardCalibration sample()
{
	return test::sampleBoardCalibration();
}

std::string replaceLine(std::string text, const std::string &from, const std::string &to)
{
	size_t at = text.find(from);
	EXPECT_NE(at, std::string::npos) << from;
	return text.replace(at, from.size(), to);
}

int lineOf(const std::string &text, const std::string &what)
{
	size_t at = text.find(what);
	return 1 + int(std::count(text.begin(), text.begin() + at, '\n'));
}

} // namespace

TEST(BoardCalibrationFile, RoundTripsExactly)
{
	std::string text = formatBoardCalibration(sample());
	BoardCalibrationResult r = parseBoardCalibration(text, "board.toml");
	ASSERT_TRUE(r.ok()) << r.errors.front().toString();
	EXPECT_EQ(r.calibration.colourToBoard, sample().colourToBoard);
	EXPECT_EQ(r.calibration.boardHeight, 780);
	EXPECT_EQ(r.calibration.date, sample().date);
}

// The lens's terms are written and read back exactly; a file of the first
// kind, without them, is a pinhole; a lens that folds the image is refused.
TEST(BoardCalibrationFile, TheLensTermsRoundTripAndAreOptional)
{
	BoardCalibration c = sample();
	c.lensK1 = -0.0341234567;
	c.lensK2 = 0.00641;
	std::string text = formatBoardCalibration(c);
	BoardCalibrationResult r = parseBoardCalibration(text, "board.toml");
	ASSERT_TRUE(r.ok()) << r.errors.front().toString();
	EXPECT_EQ(r.calibration.lensK1, c.lensK1);
	EXPECT_EQ(r.calibration.lensK2, c.lensK2);
	EXPECT_FALSE(r.calibration.lens().isPinhole());

	size_t a = text.find("lens_k1"), b = text.find('\n', text.find("lens_k2"));
	std::string old = text;
	old.erase(a, b + 1 - a);
	r = parseBoardCalibration(old, "board.toml");
	ASSERT_TRUE(r.ok()) << r.errors.front().toString();
	EXPECT_TRUE(r.calibration.lens().isPinhole());

	std::string k1 = text.substr(a, text.find('\n', a) - a);
	r = parseBoardCalibration(replaceLine(text, k1, "lens_k1 = -0.9"), "board.toml");
	ASSERT_EQ(r.errors.size(), 1u);
	EXPECT_EQ(r.errors[0].key, "board.lens_k1");
	EXPECT_NE(r.errors[0].message.find("fold"), std::string::npos) << r.errors[0].message;
	r = parseBoardCalibration(replaceLine(text, k1, "lens_k1 = nan"), "board.toml");
	ASSERT_FALSE(r.ok());
	EXPECT_EQ(r.errors[0].key, "board.lens_k1");
	EXPECT_EQ(r.errors[0].line, lineOf(text, "lens_k1 ="));
}

TEST(BoardCalibrationFile, ACutFileIsRefusedAtItsLastLine)
{
	std::string text = formatBoardCalibration(sample());
	std::string cut = text.substr(0, text.find("[end]"));
	BoardCalibrationResult r = parseBoardCalibration(cut, "board.toml");
	ASSERT_FALSE(r.ok());
	EXPECT_EQ(r.errors.back().key, "end");
	EXPECT_NE(r.errors.back().message.find("cut short"), std::string::npos);
	EXPECT_GT(r.errors.back().line, 5);
	// Cut in the middle of the matrix: a syntax error with its place.
	std::string mid = text.substr(0, text.find("homography") + 20);
	r = parseBoardCalibration(mid, "board.toml");
	ASSERT_FALSE(r.ok());
	EXPECT_EQ(r.errors.front().file, "board.toml");
	EXPECT_EQ(r.errors.front().line, lineOf(text, "homography"));
}

TEST(BoardCalibrationFile, ASingularOrIncompleteHomographyIsRefusedWhereItIs)
{
	std::string text = formatBoardCalibration(sample());
	size_t start = text.find("homography = ");
	std::string line = text.substr(start, text.find('\n', start) - start);
	std::string singular = replaceLine(text, line, "homography = [1, 2, 0, 2, 4, 0, 0, 0, 1]");
	BoardCalibrationResult r = parseBoardCalibration(singular, "board.toml");
	ASSERT_EQ(r.errors.size(), 1u);
	EXPECT_EQ(r.errors[0].key, "board.homography");
	EXPECT_EQ(r.errors[0].line, lineOf(text, "homography = "));
	EXPECT_NE(r.errors[0].message.find("singular"), std::string::npos);

	r = parseBoardCalibration(replaceLine(text, line, "homography = [1, 0, 0, 0, 1, 0, 0, 0]"), "board.toml");
	ASSERT_FALSE(r.ok());
	EXPECT_EQ(r.errors[0].key, "board.homography");

	r = parseBoardCalibration(replaceLine(text, "board_width = 1920", "board_width = 0"), "board.toml");
	ASSERT_FALSE(r.ok());
	EXPECT_EQ(r.errors[0].key, "board.board_width");
	EXPECT_EQ(r.errors[0].line, lineOf(text, "board_width"));

	r = parseBoardCalibration(replaceLine(text, "points = 45\n", ""), "board.toml");
	ASSERT_FALSE(r.ok());
	EXPECT_EQ(r.errors[0].key, "board.points");
	EXPECT_EQ(r.errors[0].message, "missing");
}

TEST(BoardCalibrationFile, TheWriterReplacesAtomicallyAndNeverWritesABadFile)
{
	auto dir = std::filesystem::temp_directory_path() / ("depthkey-boardfile-" + std::to_string(getpid()));
	std::filesystem::create_directories(dir);
	std::string path = (dir / "board.toml").string();
	std::string error;
	ASSERT_EQ(writeBoardCalibration(path, sample(), error), 0) << error;
	BoardCalibration bad = sample();
	bad.colourToBoard.h = { 0, 0, 0, 0, 0, 0, 0, 0, 1 };
	EXPECT_EQ(writeBoardCalibration(path, bad, error), -EINVAL);
	EXPECT_NE(error.find("refusing"), std::string::npos);
	BoardCalibrationResult r = loadBoardCalibration(path);
	ASSERT_TRUE(r.ok());
	EXPECT_EQ(r.calibration.colourToBoard, sample().colourToBoard);
	r = loadBoardCalibration((dir / "missing.toml").string());
	ASSERT_FALSE(r.ok());
	EXPECT_NE(r.errors[0].message.find("cannot"), std::string::npos);
	std::filesystem::remove_all(dir);
}
