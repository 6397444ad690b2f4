// Regression tests of issue 14 for the config and calibration readers: files
// that are devices, FIFOs, symlinks to them or far too large are refused at
// once with a clear error, without blocking and before a byte is read; a
// file with thousands of mistakes reports the first 20 and how many more.
#include "config/calibration_file.hpp"
#include "config/config_loader.hpp"
#include "config/text_file.hpp"
#include "tests/hostile_files.hpp"
#include "tests/sample_calibration.hpp"

#include <gtest/gtest.h>

#include <fstream>

using namespace depthkey;
using depthkey::test::FifoWithWriter;
using depthkey::test::makeSparseFile;
using depthkey::test::ScratchDir;

namespace {

std::string onlyMessage(const std::vector<ConfigError> &errors)
{
	return errors.size() == 1 ? errors[0].toString() : "(" + std::to_string(errors.size()) + " errors)";
}

} // namespace

// Case A: --check-config /dev/zero aborted with std::bad_alloc.
TEST(HostileConfigFile, CharacterDeviceIsRefused)
{
	ConfigResult result = loadConfig("/dev/zero");
	EXPECT_EQ(onlyMessage(result.errors),
		  "/dev/zero: cannot read config file: not a regular file (a character device)");
}

// Cases A and M: a 3 GB sparse file and a 50 MB one are refused by size,
// from fstat(), without reading them.
TEST(HostileConfigFile, OversizedFileIsRefusedBeforeReading)
{
	ScratchDir dir;
	ASSERT_TRUE(makeSparseFile(dir / "huge.toml", 3'000'000'000LL));
	EXPECT_EQ(onlyMessage(loadConfig(dir / "huge.toml").errors),
		  dir / "huge.toml" + ": cannot read config file: too large: 3000000000 bytes, at most 1048576");
	ASSERT_TRUE(makeSparseFile(dir / "big.toml", 50LL << 20));
	EXPECT_NE(onlyMessage(loadConfig(dir / "big.toml").errors).find("too large: 52428800 bytes"),
		  std::string::npos);

	// At the cap is still a config: comments only, so it loads.
	std::string text(kMaxConfigFileBytes, '#');
	text.back() = '\n';
	std::ofstream(dir / "cap.toml") << text;
	EXPECT_TRUE(loadConfig(dir / "cap.toml").ok());
}

// Case B: a FIFO hung --check-config in open(). The writer thread would
// unblock a blocking open, so without the fix this fails instead of hanging.
TEST(HostileConfigFile, FifoIsRefusedWithoutBlocking)
{
	ScratchDir dir;
	FifoWithWriter fifo(dir / "fifo.toml", "[colour]\nwidth = 320\n");
	ASSERT_TRUE(fifo.ok());
	EXPECT_EQ(onlyMessage(loadConfig(dir / "fifo.toml").errors),
		  dir / "fifo.toml" + ": cannot read config file: not a regular file (a FIFO)");
}

// Case C: the config replaced by a symlink to /dev/zero.
TEST(HostileConfigFile, SymlinkToADeviceIsRefused)
{
	ScratchDir dir;
	ASSERT_EQ(symlink("/dev/zero", (dir / "depthkey.toml").c_str()), 0);
	EXPECT_EQ(onlyMessage(loadConfig(dir / "depthkey.toml").errors),
		  dir / "depthkey.toml" + ": cannot read config file: not a regular file (a character device)");
}

// Cases E and F: mapping.calibration_file = "/dev/zero" aborted the daemon
// at start; a FIFO hung it.
TEST(HostileCalibrationFile, DeviceFifoAndOversizedFileAreRefused)
{
	EXPECT_EQ(onlyMessage(loadCalibration("/dev/zero").errors),
		  "/dev/zero: cannot read calibration file: not a regular file (a character device)");
	ScratchDir dir;
	FifoWithWriter fifo(dir / "cal.toml", formatCalibration(test::sampleCalibration()));
	ASSERT_TRUE(fifo.ok());
	EXPECT_EQ(onlyMessage(loadCalibration(dir / "cal.toml").errors),
		  dir / "cal.toml" + ": cannot read calibration file: not a regular file (a FIFO)");
	ASSERT_TRUE(makeSparseFile(dir / "big.toml", 10LL << 20));
	EXPECT_NE(onlyMessage(loadCalibration(dir / "big.toml").errors).find("too large"), std::string::npos);

	std::ofstream(dir / "good.toml") << formatCalibration(test::sampleCalibration());
	EXPECT_TRUE(loadCalibration(dir / "good.toml").ok());
}

// Case L: 200,000 errors gave 200,048 journal lines and 64 MB that stayed.
TEST(ConfigErrorCap, TwentyErrorsThenAndNMore)
{
	std::string text = "[segmentation]\n";
	for (int i = 0; i < 200'000; i++)
		text += "k" + std::to_string(i) + " = 1\n";
	ConfigResult result = parseConfig(text, "many.toml");
	ASSERT_EQ(result.errors.size(), kMaxReportedErrors + 1);
	// The first 20 in file order, then the count of the rest.
	for (size_t i = 0; i < kMaxReportedErrors; i++)
		EXPECT_EQ(result.errors[i].line, static_cast<int>(i) + 2) << result.errors[i].toString();
	EXPECT_EQ(result.errors.back().toString(), "many.toml: and 199980 more errors");
	EXPECT_EQ(countErrors(result.errors), 200'000u);
	EXPECT_FALSE(result.ok());
}

TEST(ConfigErrorCap, CalibrationErrorsAreCappedToo)
{
	std::string text = "format = 1\n";
	for (int i = 0; i < 500; i++)
		text += "junk" + std::to_string(i) + " = 1\n";
	CalibrationResult result = parseCalibration(text, "cal.toml");
	ASSERT_EQ(result.errors.size(), kMaxReportedErrors + 1);
	EXPECT_EQ(result.errors.back().file, "cal.toml");
	EXPECT_NE(result.errors.back().message.find("more errors"), std::string::npos);
	// 500 unknown keys, plus [calibration] and [end] missing.
	EXPECT_EQ(countErrors(result.errors), 502u);
}

TEST(ConfigErrorCap, FewErrorsAreAllReported)
{
	ConfigResult result = parseConfig("[colour]\nwidth = 1\nheight = 1\n", "few.toml");
	ASSERT_EQ(result.errors.size(), 2u);
	EXPECT_EQ(countErrors(result.errors), 2u);
	EXPECT_EQ(result.errors[1].omitted, 0u);
}

// Found by profiling the config fuzzer: every unknown key was compared in
// full with every known one, so a 1 MB key (or 50,000 unknown ones) cost a
// reload about 0.3 s of edit distances. The distance now stops at the
// suggestion's bound; what is suggested stays the same.
TEST(ConfigErrorCap, SuggestionsSurviveTheBoundedEditDistance)
{
	auto message = [](const std::string &key) {
		ConfigResult result = parseConfig("[segmentation]\n" + key + " = 1\n", "typo.toml");
		return result.errors.size() == 1 ? result.errors[0].message : "(" + std::to_string(result.errors.size()) + " errors)";
	};
	EXPECT_EQ(message("near_nm"), "unknown key (did you mean \"near_mm\"?)");    // distance 1
	EXPECT_EQ(message("naer_mm"), "unknown key (did you mean \"near_mm\"?)");    // distance 2
	EXPECT_EQ(message("nearmm_x"), "unknown key");                             // distance 3
	EXPECT_EQ(message("near_mm" + std::string(500'000, 'x')), "unknown key"); // far longer
	EXPECT_EQ(message("x"), "unknown key");                                    // far shorter
}

// Case I: a group the system does not have passed --check-config, then no
// frame was published. Now it is a config error at its place.
TEST(HostileConfigFile, UnknownOutputGroupIsAConfigError)
{
	ConfigResult result = parseConfig("[output]\ngroup = \"nosuchgroup\"\n", "group.toml");
	EXPECT_EQ(onlyMessage(result.errors),
		  "group.toml:2:9: output.group: \"nosuchgroup\" is not a group on this system (see getent group)");
	// "root" exists everywhere; a gid is taken as it is, like the writer does.
	EXPECT_TRUE(parseConfig("[output]\ngroup = \"root\"\n", "group.toml").ok());
	EXPECT_TRUE(parseConfig("[output]\ngroup = \"4242\"\n", "group.toml").ok());
}
