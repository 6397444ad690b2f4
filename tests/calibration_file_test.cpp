// The calibration file: round trip, every class of error with its place,
// files cut short, and the atomic writer that never replaces a good file
// with a bad one.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <dirent.h>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <sys/stat.h>
#include <unistd.h>

#include "config/calibration_file.hpp"
#include "tests/sample_calibration.hpp"

namespace depthkey {
namespace {

using test::sampleCalibration;

const std::string kFile = "cal.toml";

// The text of the sample with one line replaced (or removed when to is "").
std::string sampleWith(const std::string &from, const std::string &to)
{
	std::string text = formatCalibration(sampleCalibration());
	size_t at = text.find(from);
	EXPECT_NE(at, std::string::npos) << from;
	if (at != std::string::npos)
		text.replace(at, from.size(), to);
	return text;
}

std::string lineStarting(const std::string &text, const std::string &prefix)
{
	size_t at = text.find("\n" + prefix);
	if (at == std::string::npos)
		return "";
	return text.substr(at + 1, text.find('\n', at + 1) - at - 1);
}

// The one error text produces, as the technician reads it.
std::string onlyError(const std::string &text)
{
	CalibrationResult result = parseCalibration(text, kFile);
	EXPECT_EQ(result.errors.size(), 1u);
	for (const ConfigError &e : result.errors)
		std::cerr << "  " << e.toString() << '\n';
	return result.errors.empty() ? "" : result.errors[0].toString();
}

int lineOf(const std::string &text, const std::string &needle)
{
	size_t at = text.find(needle);
	return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(at), '\n'));
}

std::string readFile(const std::string &path)
{
	std::ifstream in(path);
	std::stringstream text;
	text << in.rdbuf();
	return text.str();
}

class TempDir
{
public:
	TempDir()
	{
		char templ[] = "/tmp/depthkey-cal-XXXXXX";
		path_ = mkdtemp(templ) ? templ : "";
	}
	~TempDir()
	{
		std::error_code ignored; // a leftover temp folder fails no test
		if (!path_.empty())
			std::filesystem::remove_all(path_, ignored);
	}
	const std::string &path() const { return path_; }
	std::vector<std::string> entries() const
	{
		std::vector<std::string> names;
		if (DIR *dir = opendir(path_.c_str())) {
			while (dirent *e = readdir(dir))
				if (e->d_name[0] != '.')
					names.push_back(e->d_name);
			closedir(dir);
		}
		return names;
	}

private:
	std::string path_;
};

TEST(CalibrationFile, RoundTripIsExact)
{
	Calibration c = sampleCalibration();
	CalibrationResult result = parseCalibration(formatCalibration(c), kFile);
	for (const ConfigError &e : result.errors)
		ADD_FAILURE() << e.toString();
	ASSERT_TRUE(result.ok());
	const Calibration &r = result.calibration;
	EXPECT_EQ(r.mapping.kind, MappingKind::Parallax);
	EXPECT_EQ(r.mapping.x, c.mapping.x);    // bit for bit
	EXPECT_EQ(r.mapping.y, c.mapping.y);
	EXPECT_EQ(r.mapping.colourWidth, 640);
	EXPECT_EQ(r.mapping.tofHeight, 124);
	EXPECT_EQ(r.date, c.date);
	EXPECT_EQ(r.colourCamera, c.colourCamera);
	EXPECT_EQ(r.tofCamera, c.tofCamera);
	EXPECT_EQ(r.selectedBy, "heldout");
	EXPECT_EQ(r.heldOutViews, c.heldOutViews);
	EXPECT_EQ(r.depthsM, c.depthsM);
	ASSERT_EQ(r.summaries.size(), 2u);
	EXPECT_EQ(r.summaries[1].model, MappingKind::Parallax);
	EXPECT_EQ(r.summaries[1].heldOut.points, 25);
	EXPECT_DOUBLE_EQ(r.summaries[1].heldOut.maxPx, 1.3);
	ASSERT_EQ(r.residuals.size(), c.residuals.size());
	EXPECT_TRUE(r.residuals[1].heldOut);
	EXPECT_DOUBLE_EQ(r.residuals[2].depthM, 1.4);
	EXPECT_DOUBLE_EQ(r.residuals[2].stats.rmsPx, 0.25);
}

TEST(CalibrationFile, PaperModelHasFiveCoefficientsPerAxis)
{
	Calibration c = sampleCalibration();
	c.mapping.kind = MappingKind::Paper;
	std::string text = formatCalibration(c);
	CalibrationResult result = parseCalibration(text, kFile);
	ASSERT_TRUE(result.ok());
	std::string x = lineStarting(text, "x = ");
	EXPECT_EQ(std::count(x.begin(), x.end(), ','), 4) << x;
	EXPECT_EQ(result.calibration.mapping.kind, MappingKind::Paper);
	EXPECT_EQ(result.calibration.mapping.x[4], c.mapping.x[4]);
	EXPECT_EQ(result.calibration.mapping.x[5], 0.0);
}

TEST(CalibrationFile, UnknownKeyIsNamedWithItsPlace)
{
	std::string text = sampleWith("tof_width = 160\n", "tof_width = 160\ntof_widht = 160\n");
	EXPECT_EQ(onlyError(text), kFile + ":" + std::to_string(lineOf(text, "tof_widht")) +
					   ":1: calibration.tof_widht: unknown key (did you mean \"tof_width\"?)");
}

TEST(CalibrationFile, WrongTypeIsNamedWithItsPlace)
{
	std::string text = sampleWith("colour_width = 640", "colour_width = \"640\"");
	EXPECT_EQ(onlyError(text), kFile + ":" + std::to_string(lineOf(text, "colour_width")) +
					   ":16: calibration.colour_width: expected an integer, got a string");
}

TEST(CalibrationFile, WrongCoefficientCountIsRefused)
{
	std::string text = formatCalibration(sampleCalibration());
	std::string x = lineStarting(text, "x = ");
	std::string shorter = x.substr(0, x.rfind(',')) + "]";
	text.replace(text.find(x), x.size(), shorter);
	EXPECT_EQ(onlyError(text), kFile + ":" + std::to_string(lineOf(text, "x = ")) +
					   ":5: calibration.x: has 13 numbers, expected 14");
}

TEST(CalibrationFile, NonFiniteCoefficientIsRefusedAtItsElement)
{
	for (const char *bad : { "nan", "inf", "-inf", "1e300" }) {
		std::string text = sampleWith("x = [319.2, ", std::string("x = [") + bad + ", ");
		std::string error = onlyError(text);
		EXPECT_NE(error.find(kFile + ":" + std::to_string(lineOf(text, "x = ")) +
				     ":6: calibration.x[0]: "),
			  std::string::npos)
			<< error;
		EXPECT_NE(error.find("is out of range"), std::string::npos) << error;
	}
}

TEST(CalibrationFile, IdentityAndUnknownModelsAreRefused)
{
	EXPECT_EQ(onlyError(sampleWith("model = \"parallax\"\ndate", "model = \"identity\"\ndate")),
		  kFile + ":7:9: calibration.model: \"identity\" is not one of \"paper\" \"parallax\"");
}

TEST(CalibrationFile, ModelMustMatchItsCoefficients)
{
	// A paper model with fourteen coefficients is not a paper model.
	CalibrationResult result = parseCalibration(
		sampleWith("model = \"parallax\"\ndate", "model = \"paper\"\ndate"), kFile);
	ASSERT_EQ(result.errors.size(), 2u);
	EXPECT_EQ(result.errors[0].toString(), kFile + ":18:5: calibration.x: has 14 numbers, expected 5");
	EXPECT_EQ(result.errors[1].toString(), kFile + ":19:5: calibration.y: has 14 numbers, expected 5");
}

TEST(CalibrationFile, MissingKeyIsReportedAtItsSection)
{
	std::string text = formatCalibration(sampleCalibration());
	std::string line = lineStarting(text, "tof_camera = ");
	text.erase(text.find(line), line.size() + 1);
	EXPECT_EQ(onlyError(text), kFile + ":" + std::to_string(lineOf(text, "[calibration]")) +
					   ":1: calibration.tof_camera: missing");
}

TEST(CalibrationFile, DepthsMustBeAscending)
{
	EXPECT_EQ(onlyError(sampleWith("depths_m = [0.8, 1.4, 2]", "depths_m = [1.4, 0.8, 2]")),
		  kFile + ":15:12: calibration.depths_m: must be in ascending order without repeats");
}

TEST(CalibrationFile, NewerFormatIsRefused)
{
	EXPECT_EQ(onlyError(sampleWith("format = 1", "format = 2")),
		  kFile + ":4:10: format: format 2 is not supported: this depthkey reads format 1");
}

TEST(CalibrationFile, SelectedModelNeedsItsSummary)
{
	std::string text = formatCalibration(sampleCalibration());
	size_t begin = text.find("[summary.parallax]");
	size_t end = text.find("\n\n", begin);
	text.erase(begin, end - begin + 1);
	std::string error = onlyError(text);
	EXPECT_NE(error.find("summary: has no [summary.parallax] for the selected model"),
		  std::string::npos)
		<< error;
}

TEST(CalibrationFile, EveryFileCutShortIsRefusedWithALine)
{
	std::string text = formatCalibration(sampleCalibration());
	int lines = lineOf(text, "complete = true");
	// Only the final newline may go: the file minus it is still whole.
	for (size_t length = 0; length + 1 < text.size(); length++) {
		CalibrationResult result = parseCalibration(text.substr(0, length), kFile);
		ASSERT_FALSE(result.ok()) << "accepted a file cut at byte " << length;
		for (const ConfigError &e : result.errors) {
			EXPECT_GE(e.line, 1) << e.toString();
			EXPECT_LE(e.line, lines) << e.toString();
		}
	}
	EXPECT_TRUE(parseCalibration(text.substr(0, text.size() - 1), kFile).ok());
}

TEST(CalibrationFile, CutAfterAResidualRowNamesTheEnd)
{
	std::string text = formatCalibration(sampleCalibration());
	text.resize(text.find("[[residuals]]"));
	CalibrationResult result = parseCalibration(text, kFile);
	ASSERT_FALSE(result.ok());
	int end = static_cast<int>(std::count(text.begin(), text.end(), '\n'));
	std::vector<std::string> errors;
	for (const ConfigError &e : result.errors)
		errors.push_back(e.toString());
	std::string at = kFile + ":" + std::to_string(end) + ":1: ";
	EXPECT_EQ(errors, (std::vector<std::string>{
				  at + "end: missing section [end]: the file is cut short",
				  at + "residuals: has no fit row for model paper at depth_m 0.8",
				  at + "residuals: has no fit row for model paper at depth_m 1.4",
				  at + "residuals: has no fit row for model paper at depth_m 2",
				  at + "residuals: has no fit row for model parallax at depth_m 0.8",
				  at + "residuals: has no fit row for model parallax at depth_m 1.4",
				  at + "residuals: has no fit row for model parallax at depth_m 2",
			  }));
}

TEST(CalibrationFile, GarbageIsRefusedWithItsPlace)
{
	CalibrationResult result = parseCalibration("format = 1\n[calibration\x01]\n", kFile);
	ASSERT_FALSE(result.ok());
	EXPECT_EQ(result.errors[0].line, 2);
}

TEST(CalibrationFile, MissingFileNamesItAndWhy)
{
	CalibrationResult result = loadCalibration("/nonexistent/cal.toml");
	ASSERT_EQ(result.errors.size(), 1u);
	EXPECT_EQ(result.errors[0].toString(),
		  "/nonexistent/cal.toml: cannot read calibration file: No such file or directory");
}

TEST(CalibrationFile, WriteThenLoad)
{
	TempDir dir;
	std::string path = dir.path() + "/cal.toml";
	std::string error;
	ASSERT_EQ(writeCalibration(path, sampleCalibration(), error), 0) << error;
	CalibrationResult result = loadCalibration(path);
	ASSERT_TRUE(result.ok());
	EXPECT_EQ(result.calibration.mapping.y, sampleCalibration().mapping.y);

	struct stat st;
	ASSERT_EQ(stat(path.c_str(), &st), 0);
	EXPECT_EQ(st.st_mode & 0777, 0644u);
	// No temporary left behind.
	EXPECT_EQ(dir.entries(), std::vector<std::string>{ "cal.toml" });
}

TEST(CalibrationFile, FailedCalibrationNeverReplacesAGoodOne)
{
	TempDir dir;
	std::string path = dir.path() + "/cal.toml";
	std::string error;
	ASSERT_EQ(writeCalibration(path, sampleCalibration(), error), 0) << error;
	std::string good = readFile(path);

	Calibration bad = sampleCalibration();
	bad.mapping.x[3] = std::nan("");
	EXPECT_EQ(writeCalibration(path, bad, error), -EINVAL);
	EXPECT_NE(error.find("calibration.x[3]"), std::string::npos) << error;

	Calibration empty = sampleCalibration();
	empty.depthsM.clear();
	EXPECT_EQ(writeCalibration(path, empty, error), -EINVAL);

	EXPECT_EQ(readFile(path), good);
	EXPECT_EQ(dir.entries(), std::vector<std::string>{ "cal.toml" });
}

TEST(CalibrationFile, UnwritableDirectoryIsAnErrorNamingIt)
{
	std::string error;
	EXPECT_EQ(writeCalibration("/nonexistent/cal.toml", sampleCalibration(), error), -ENOENT);
	EXPECT_NE(error.find("/nonexistent"), std::string::npos) << error;
}


// A calibration that fitted the board too carries it in [board]: read back
// exactly, and held to the same checks as a board file, named in this file.
TEST(CalibrationFile, BoardSectionRoundTripsAndIsChecked)
{
	Calibration c = sampleCalibration();
	EXPECT_EQ(formatCalibration(c).find("[board]"), std::string::npos) << "no board, no section";
	BoardCalibration b = test::sampleBoardCalibration(); // 640x480, as the sample mapping
	b.lensK1 = -0.034;
	b.lensK2 = 0.008;
	c.board = b;
	const std::string text = formatCalibration(c);
	CalibrationResult result = parseCalibration(text, kFile);
	for (const ConfigError &e : result.errors)
		ADD_FAILURE() << e.toString();
	ASSERT_TRUE(result.calibration.board.has_value());
	EXPECT_EQ(result.calibration.board->colourToBoard.h, b.colourToBoard.h); // bit for bit
	EXPECT_EQ(result.calibration.board->lensK1, b.lensK1);
	EXPECT_EQ(result.calibration.board->boardHeight, 780);

	// Fitted in another colour size than the mapping: refused, at the key.
	std::string other = text;
	const size_t board = other.find("[board]");
	ASSERT_NE(board, std::string::npos);
	other.replace(other.find("colour_width = 640", board), 18, "colour_width = 320");
	other.replace(other.find("colour_height = 480", board), 19, "colour_height = 240");
	std::string error = onlyError(other);
	EXPECT_NE(error.find("another colour size than the mapping"), std::string::npos) << error;
	EXPECT_NE(error.find(std::string(kFile) + ":" + std::to_string(lineOf(other, "colour_width = 320"))),
		  std::string::npos) << error;

	// A singular H is refused as in a board file.
	std::string singular = text;
	size_t at = singular.find("homography = [");
	singular.replace(at, singular.find('\n', at) - at, "homography = [0, 0, 0, 0, 0, 0, 0, 0, 1]");
	error = onlyError(singular);
	EXPECT_NE(error.find("homography"), std::string::npos) << error;
	EXPECT_NE(error.find("singular"), std::string::npos) << error;
}

} // namespace
} // namespace depthkey
