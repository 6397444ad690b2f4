// depthkey-calibrate --print-pattern (issue 30): the depth pattern written
// as PDF and SVG on A4 and A3 parses, has the paper's true size, and printed
// at a known resolution shows the 7x5 grid the detector finds, its circles
// the stated number of millimetres apart.
#include "algo/circle_grid_detector.hpp"
#include "hal/image_file.hpp"
#include "tests/process/shell_command.hpp"
#include "tests/test_paths.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <unistd.h>

using namespace depthkey;

namespace {

std::string tempDir()
{
	auto dir = std::filesystem::temp_directory_path() / ("depthkey-print-pattern-" + std::to_string(getpid()));
	std::filesystem::remove_all(dir);
	std::filesystem::create_directories(dir);
	return dir.string();
}

struct Paper {
	const char *name;
	double widthMm, heightMm;
};
const Paper kPapers[] = { { "a4", 297, 210 }, { "a3", 420, 297 } };

std::string printPattern(const std::string &file, const char *paper, int &status)
{
	return test::run(test::binDir() + "/depthkey-calibrate --print-pattern " + file + " --paper " + paper, status);
}

// "... 7x5 circles 32 mm apart ..." from the tool's line.
double statedSpacingMm(const std::string &out)
{
	size_t at = out.find("circles ");
	double mm = 0;
	return at != std::string::npos && std::sscanf(out.c_str() + at, "circles %lf mm apart", &mm) == 1 ? mm : 0;
}

} // namespace

TEST(PrintPattern, PdfHasThePapersSizeAndTheStatedSpacing)
{
	std::string dir = tempDir();
	for (const Paper &paper : kPapers) {
		SCOPED_TRACE(paper.name);
		std::string pdf = dir + "/pattern-" + paper.name + ".pdf";
		int status = 0;
		std::string out = printPattern(pdf, paper.name, status);
		ASSERT_EQ(status, 0) << out;
		double spacing = statedSpacingMm(out);
		ASSERT_GT(spacing, 10) << out;

		// poppler's pdfinfo parses the file: one page of the paper's size.
		std::string info = test::run("pdfinfo " + pdf, status);
		ASSERT_EQ(status, 0) << info;
		double wPt = 0, hPt = 0;
		size_t at = info.find("Page size:");
		ASSERT_NE(at, std::string::npos) << info;
		ASSERT_EQ(std::sscanf(info.c_str() + at, "Page size: %lf x %lf pts", &wPt, &hPt), 2) << info;
		EXPECT_NEAR(wPt * 25.4 / 72, paper.widthMm, 0.1);
		EXPECT_NEAR(hPt * 25.4 / 72, paper.heightMm, 0.1);
		EXPECT_NE(info.find("Pages:           1"), std::string::npos) << info;

		// Printed at 50 dpi, the detector finds the grid, the stated mm apart.
		// The page without its bottom 25 mm: at 50 dpi the line of text's
		// letters are blobs the size of circles (a camera at 0.9 m sees them
		// a pixel across).
		constexpr double kDpi = 50;
		int height = int((paper.heightMm - 25) / 25.4 * kDpi);
		std::string out2 = test::run("pdftoppm -r 50 -singlefile -png -x 0 -y 0 -W 10000 -H " + std::to_string(height) +
						     " " + pdf + " " + dir + "/page",
					     status);
		ASSERT_EQ(status, 0) << out2;
		RgbImage page;
		std::string error;
		ASSERT_EQ(readRgbImage(dir + "/page.png", page, error), 0) << error;
		EXPECT_NEAR(page.width(), paper.widthMm / 25.4 * kDpi, 1.0);
		std::vector<ImagePoint> centres;
		ASSERT_EQ(findColourGrid(page, GridSize{}, centres), 0);
		double along = (centres[6].x - centres[0].x) / 6, down = (centres[28].y - centres[0].y) / 4;
		EXPECT_NEAR(along * 25.4 / kDpi, spacing, 0.3);
		EXPECT_NEAR(down * 25.4 / kDpi, spacing, 0.3);
		// The grid is centred across the page.
		EXPECT_NEAR((centres[0].x + centres[6].x) / 2, page.width() / 2.0, 1.0);
	}
}

TEST(PrintPattern, SvgStatesItsSizeInMillimetres)
{
	std::string dir = tempDir();
	for (const Paper &paper : kPapers) {
		SCOPED_TRACE(paper.name);
		std::string svg = dir + "/pattern-" + paper.name + ".svg";
		int status = 0;
		std::string out = printPattern(svg, paper.name, status);
		ASSERT_EQ(status, 0) << out;
		std::ifstream in(svg);
		std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
		char expected[128];
		std::snprintf(expected, sizeof(expected), "width=\"%gmm\" height=\"%gmm\" viewBox=\"0 0 %g %g\"",
			      paper.widthMm, paper.heightMm, paper.widthMm, paper.heightMm);
		EXPECT_NE(text.find("<svg"), std::string::npos);
		EXPECT_NE(text.find(expected), std::string::npos) << expected;
		EXPECT_NE(text.find("</svg>"), std::string::npos);
	}
}

TEST(PrintPattern, BadUseIsRefusedWithTheReason)
{
	std::string dir = tempDir();
	int status = 0;
	std::string out = printPattern(dir + "/pattern.png", "a4", status);
	EXPECT_EQ(status, 1);
	EXPECT_NE(out.find(dir + "/pattern.png: the file's name must end in .pdf or .svg"), std::string::npos) << out;
	out = printPattern("/nonexistent-dir/pattern.pdf", "a4", status);
	EXPECT_EQ(status, 1);
	EXPECT_NE(out.find("/nonexistent-dir/pattern.pdf: No such file or directory"), std::string::npos) << out;
	out = printPattern(dir + "/pattern.pdf", "letter", status);
	EXPECT_EQ(status, 2);
	EXPECT_NE(out.find("--paper letter"), std::string::npos) << out;
	EXPECT_FALSE(std::filesystem::exists(dir + "/pattern.pdf"));
}
