// depthkey-eval as scripts use it: its summary line, the same scores from
// the simulator and from the sequence it saved, clear errors.
#include "tests/shell_command.hpp"
#include "tests/test_paths.hpp"

#include <cstdio>
#include <filesystem>
#include <gtest/gtest.h>
#include <string>

using depthkey::test::lastLine;
using depthkey::test::run;

TEST(EvalTool, SummaryLineAndSequenceRoundTrip)
{
	std::string eval = depthkey::test::binDir() + "/depthkey-eval --config " + depthkey::test::sourceDir() +
			   "/config/depthkey.toml";
	std::string dir = std::filesystem::temp_directory_path() / ("depthkey-eval-" + std::to_string(getpid()));
	int status;
	std::string sim = run(eval + " --sim 2 --frames 12 --method depth-only --save-sequence " + dir, status);
	ASSERT_EQ(status, 0) << sim;
	std::string summary = lastLine(sim);
	// Exactly the documented form: parse it, print it again, compare.
	double iou, bf, fnr, fpr;
	long fps;
	ASSERT_EQ(std::sscanf(summary.c_str(), "summary method=depth-only frames=12 iou=%lf bf=%lf fnr=%lf fpr=%lf fps=%ld",
			      &iou, &bf, &fnr, &fpr, &fps), 5)
		<< summary;
	char again[160];
	std::snprintf(again, sizeof(again), "summary method=depth-only frames=12 iou=%.3f bf=%.3f fnr=%.3f fpr=%.3f fps=%ld",
		      iou, bf, fnr, fpr, fps);
	EXPECT_EQ(summary, again);
	for (double v : { iou, bf, fnr, fpr }) {
		EXPECT_GE(v, 0.0);
		EXPECT_LE(v, 1.0);
	}

	std::string replayed = run(eval + " --sequence " + dir + " --method depth-only", status);
	ASSERT_EQ(status, 0) << replayed;
	// Everything but the speed is the same: the recording is lossless.
	auto scores = [](const std::string &line) { return line.substr(0, line.find(" fps=")); };
	EXPECT_EQ(scores(lastLine(replayed)), scores(summary));
	std::filesystem::remove_all(dir);
}

TEST(EvalTool, BadArgumentsAndMissingTruthAreClearErrors)
{
	std::string eval = depthkey::test::binDir() + "/depthkey-eval";
	int status;
	std::string out = run(eval + " --sim 1", status);
	EXPECT_EQ(status, 2);
	EXPECT_NE(out.find("--sim needs --frames N"), std::string::npos) << out;
	out = run(eval + " --sim 1 --frames 3 --method magic", status);
	EXPECT_EQ(status, 2);
	EXPECT_NE(out.find("--method must be depth-only or pipeline"), std::string::npos) << out;
	out = run(eval + " --sequence /nonexistent/seq", status);
	EXPECT_EQ(status, 1);
	EXPECT_NE(out.find("/nonexistent/seq"), std::string::npos) << out;
}
