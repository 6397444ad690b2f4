// The config keys of the segmentation pipeline: defaults, ranges, the
// amplitude interval, and the shipped depthkey.toml matching the defaults.
#include "config/config_loader.hpp"
#include "tests/test_paths.hpp"

#include <gtest/gtest.h>

using namespace depthkey;

namespace {

std::string firstError(const std::string &text)
{
	ConfigResult r = parseConfig(text, "t.toml");
	return r.errors.empty() ? "" : r.errors.front().toString();
}

} // namespace

TEST(ConfigPipeline, ShippedFileHasTheDefaults)
{
	ConfigResult r = loadConfig(test::sourceDir() + "/config/depthkey.toml");
	ASSERT_TRUE(r.ok()) << r.errors.front().toString();
	Settings defaults;
	EXPECT_EQ(r.settings.segmentation, defaults.segmentation);
	EXPECT_EQ(r.settings.mapping, defaults.mapping);
	EXPECT_EQ(r.settings.learning, defaults.learning);
	EXPECT_EQ(r.settings.siox, defaults.siox);
	EXPECT_EQ(r.settings.composite, defaults.composite);
}

TEST(ConfigPipeline, ValuesAreBound)
{
	ConfigResult r = parseConfig("[segmentation]\nmin_amplitude = 10\nmax_amplitude = 20000\nerode_px = 3\n"
				     "dilate_px = 9\nsurface_px = 11\n[mapping]\ncalibration_file = \"/etc/depthkey/cal.toml\"\n"
				     "[learning]\ninitial_frames = 5\nboard_rate = 0.5\nlecturer_rate = 0\nsamples = 1000\n"
				     "margin_px = 0\nrelearn_misfit = 0.2\n[siox]\nsmoothing = 0\nsoft_alpha = false\n"
				     "[board]\nbackend = \"image\"\nimage = \"/srv/board.png\"\n",
				     "t.toml");
	ASSERT_TRUE(r.ok()) << r.errors.front().toString();
	EXPECT_EQ(r.settings.segmentation.maxAmplitude, 20000);
	EXPECT_EQ(r.settings.segmentation.dilatePx, 9);
	EXPECT_EQ(r.settings.segmentation.surfacePx, 11);
	EXPECT_EQ(r.settings.mapping.calibrationFile, "/etc/depthkey/cal.toml");
	EXPECT_EQ(r.settings.learning.samples, 1000);
	EXPECT_DOUBLE_EQ(r.settings.learning.boardRate, 0.5);
	EXPECT_EQ(r.settings.siox.smoothing, 0);
	EXPECT_FALSE(r.settings.siox.softAlpha);
	EXPECT_EQ(r.settings.board.image, "/srv/board.png");
}

TEST(ConfigPipeline, OutOfRangeAndInconsistentValuesAreRefused)
{
	EXPECT_NE(firstError("[segmentation]\nerode_px = 21\n").find("segmentation.erode_px"), std::string::npos);
	EXPECT_NE(firstError("[segmentation]\ndilate_px = 0\n").find("segmentation.dilate_px"), std::string::npos);
	EXPECT_NE(firstError("[segmentation]\nsurface_px = 0\n").find("segmentation.surface_px"), std::string::npos);
	EXPECT_NE(firstError("[segmentation]\nsurface_px = 41\n").find("segmentation.surface_px"), std::string::npos);
	EXPECT_NE(firstError("[segmentation]\nmin_amplitude = 500\nmax_amplitude = 400\n").find("max_amplitude"),
		  std::string::npos);
	EXPECT_NE(firstError("[mapping]\ncalibration_file = \"cal.toml\"\n").find("absolute"), std::string::npos);
	EXPECT_NE(firstError("[learning]\nboard_rate = 1.5\n").find("learning.board_rate"), std::string::npos);
	EXPECT_NE(firstError("[learning]\nsamples = 10\n").find("learning.samples"), std::string::npos);
	EXPECT_NE(firstError("[siox]\nsmoothing = 9\n").find("siox.smoothing"), std::string::npos);
	EXPECT_NE(firstError("[siox]\nsoft = true\n").find("siox.soft"), std::string::npos);
	EXPECT_NE(firstError("[board]\nimage = \"b.png\"\n").find("board.image"), std::string::npos);
	// The board's keys moved from [composite] to [board]: the error says where.
	EXPECT_NE(firstError("[composite]\nboard_colour = 0x102030\n").find("has moved: [board] colour"), std::string::npos);
	EXPECT_NE(firstError("[composite]\nboard_image = \"/b.png\"\n").find("composite.board_image: has moved"),
		  std::string::npos);
	EXPECT_NE(firstError("[board]\nbackend = \"image\"\n").find("board.image: must name"), std::string::npos);
	EXPECT_NE(firstError("[board]\noutput_width = 1280\n").find("both be 0"), std::string::npos);
	EXPECT_NE(firstError("[board]\nbackend = \"hdmi\"\n").find("board.backend"), std::string::npos);
	EXPECT_NE(firstError("[output]\nboard_lecturer_name = \"/depthkey.composite\"\n").find("must differ"),
		  std::string::npos);
	EXPECT_NE(firstError("[leds]\nboard_line = 5\n").find("use the same line 5"), std::string::npos);
}
