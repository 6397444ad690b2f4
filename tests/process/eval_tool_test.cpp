// depthkey-eval as scripts use it: its summary line, the same scores from
// the simulator and from the sequence it saved, clear errors.
#include "tests/process/shell_command.hpp"
#include "tests/test_paths.hpp"

#include <cstdio>
#include <filesystem>
#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
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
	double iou, bf, fnr, fpr, bfScaled;
	long fps;
	int scaledPx;
	ASSERT_EQ(std::sscanf(summary.c_str(),
			      "summary method=depth-only frames=12 iou=%lf bf=%lf fnr=%lf fpr=%lf fps=%ld bf_scaled=%lf "
			      "bf_scaled_px=%d",
			      &iou, &bf, &fnr, &fpr, &fps, &bfScaled, &scaledPx),
		  7)
		<< summary;
	char again[200];
	std::snprintf(again, sizeof(again),
		      "summary method=depth-only frames=12 iou=%.3f bf=%.3f fnr=%.3f fpr=%.3f fps=%ld bf_scaled=%.3f "
		      "bf_scaled_px=%d",
		      iou, bf, fnr, fpr, fps, bfScaled, scaledPx);
	EXPECT_EQ(summary, again);
	// The simulated lecture is 640x480: the scaled tolerance is the 2 px.
	EXPECT_EQ(scaledPx, 2);
	EXPECT_EQ(bfScaled, bf);
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

// Issue 14, case O: one mis-sized frame was scored 0, and eval exited 0
// without a word. Now it names the frame and both sizes, and fails.
TEST(EvalTool, MisSizedFrameIsAnError)
{
	std::string eval = depthkey::test::binDir() + "/depthkey-eval --config " + depthkey::test::sourceDir() +
			   "/config/depthkey.toml";
	std::string dir = std::filesystem::temp_directory_path() / ("depthkey-eval-size-" + std::to_string(getpid()));
	int status;
	std::string out = run(eval + " --sim 2 --frames 6 --method depth-only --save-sequence " + dir, status);
	ASSERT_EQ(status, 0) << out;
	std::string victim;
	for (const auto &entry : std::filesystem::directory_iterator(dir + "/rgb"))
		if (victim.empty() || entry.path().string() > victim)
			victim = entry.path().string(); // the last frame
	cv::Mat frame = cv::imread(victim, cv::IMREAD_COLOR), half;
	ASSERT_FALSE(frame.empty()) << victim;
	cv::resize(frame, half, cv::Size(frame.cols / 2, frame.rows / 2));
	ASSERT_TRUE(cv::imwrite(victim, half));

	out = run(eval + " --sequence " + dir + " --method depth-only", status);
	EXPECT_EQ(status, 1) << out;
	std::string name = victim.substr(dir.size() + 1);
	std::string expected = name + " is " + std::to_string(half.cols) + "x" + std::to_string(half.rows) +
			       ", but the sequence's frames are " + std::to_string(frame.cols) + "x" +
			       std::to_string(frame.rows);
	EXPECT_NE(out.find(expected), std::string::npos) << out;
	EXPECT_EQ(out.find("summary method="), std::string::npos) << out;
	std::filesystem::remove_all(dir);
}
