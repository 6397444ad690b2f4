// board.backend "image": the picture is read again when the board's computer
// replaces the file (by rename, the normal case, or written in place), and a
// half-written or broken file is refused with its error while the last good
// picture stays (the source delivers nothing and reports Lost).
#include "hal/board/image_board_source.hpp"
#include "tests/image_codecs.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include <cstdio>
#include <filesystem>
#include <fcntl.h>
#include <functional>
#include <unistd.h>
#include <vector>

using namespace depthkey;

namespace {

std::vector<uchar> encodePng(Rgb8 colour, int w = 32, int h = 24)
{
	cv::Mat mat(h, w, CV_8UC3, cv::Scalar(colour.b, colour.g, colour.r));
	std::vector<uchar> bytes;
	cv::imencode(".png", mat, bytes);
	return bytes;
}

void writeBytes(const std::string &path, const std::vector<uchar> &bytes, size_t count)
{
	int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
	ASSERT_GE(fd, 0);
	ASSERT_EQ(::write(fd, bytes.data(), count), ssize_t(count));
	::close(fd);
}

// As the board's computer should: a temporary file renamed over the picture.
void replaceByRename(const std::string &path, const std::vector<uchar> &bytes)
{
	writeBytes(path + ".tmp", bytes, bytes.size());
	ASSERT_EQ(std::rename((path + ".tmp").c_str(), path.c_str()), 0);
}

struct Harness {
	EventLoop loop;
	std::string dir, path;
	std::vector<Rgb8> pictures; // top-left pixel of each delivered picture
	std::vector<DeviceStatus> statuses;
	EventSource step;
	std::vector<std::function<void()>> steps;
	// A step may wait (up to 3 s) for what it needs to have happened: on a
	// loaded machine the source's read can take longer than one 50 ms step.
	std::vector<std::function<bool()>> ready;
	size_t next = 0, waited = 0;

	void then(std::function<bool()> when, std::function<void()> act)
	{
		ready.resize(steps.size());
		ready.push_back(std::move(when));
		steps.push_back(std::move(act));
	}
	std::function<bool()> picturesAtLeast(size_t n)
	{
		return [this, n] { return pictures.size() >= n; };
	}

	Harness()
	{
		dir = (std::filesystem::temp_directory_path() / ("depthkey-board-image-" + std::to_string(getpid()))).string();
		std::filesystem::remove_all(dir);
		std::filesystem::create_directories(dir);
		path = dir + "/board.png";
		EXPECT_EQ(loop.open(), 0);
	}
	~Harness() { std::filesystem::remove_all(dir); }

	// Each step 50 ms after the last, on the loop, then the loop ends.
	void run(ImageBoardSource &source)
	{
		ASSERT_EQ(source.start(loop, [this](const ColourFrame &f) { pictures.push_back(f.rgb.at(0, 0)); },
				       [this](const DeviceStatus &s) { statuses.push_back(s); }),
			  0);
		loop.addPeriodic(50000, [this] {
			if (next < steps.size()) {
				const bool gated = next < ready.size() && ready[next] && !ready[next]() && ++waited < 60;
				if (!gated) {
					waited = 0;
					steps[next++]();
				}
			} else
				loop.exit(0);
		}, step);
		loop.run();
	}
};

} // namespace

TEST(ImageBoardSource, ReadsAgainWhenTheFileIsReplacedAndRefusesAHalfWrittenOne)
{
	SKIP_WITHOUT_IMAGE_CODECS();
	Harness h;
	std::vector<uchar> red = encodePng({ 200, 10, 10 }), green = encodePng({ 10, 200, 10 }),
			   blue = encodePng({ 10, 10, 200 });
	replaceByRename(h.path, red);
	BoardSettings settings;
	settings.backend = "image";
	settings.image = h.path;
	ImageBoardSource source(settings);
	size_t afterStart = 0, afterRename = 0, afterHalf = 0, afterInPlace = 0;
	DeviceStatus halfStatus;
	h.then(h.picturesAtLeast(1), [&] { afterStart = h.pictures.size(); replaceByRename(h.path, green); });
	h.then(h.picturesAtLeast(2), [&] {
		afterRename = h.pictures.size();
		writeBytes(h.path, blue, blue.size() / 2); // the writer died half way
	});
	h.then([&] { return source.status().state == DeviceState::Lost; }, [&] {
		afterHalf = h.pictures.size();
		halfStatus = source.status();
		writeBytes(h.path, blue, blue.size()); // written in place, whole
	});
	h.then(h.picturesAtLeast(3), [&] { afterInPlace = h.pictures.size(); });
	// Another file in the folder is none of its business.
	h.steps.push_back([&] { replaceByRename(h.dir + "/other.png", red); });
	h.run(source);

	ASSERT_EQ(afterStart, 1u);
	EXPECT_EQ(h.pictures[0], (Rgb8{ 200, 10, 10 }));
	ASSERT_EQ(afterRename, 2u);
	EXPECT_EQ(h.pictures[1], (Rgb8{ 10, 200, 10 }));
	// Refused: nothing delivered (the daemon keeps green), Lost with the reader's words.
	EXPECT_EQ(afterHalf, 2u);
	EXPECT_EQ(halfStatus.state, DeviceState::Lost);
	EXPECT_NE(halfStatus.detail.find(h.path), std::string::npos) << halfStatus.detail;
	EXPECT_NE(halfStatus.detail.find("keeping the last good one"), std::string::npos) << halfStatus.detail;
	ASSERT_EQ(afterInPlace, 3u);
	EXPECT_EQ(h.pictures[2], (Rgb8{ 10, 10, 200 }));
	EXPECT_EQ(h.pictures.size(), 3u);
	EXPECT_EQ(source.status().state, DeviceState::Streaming);
	EXPECT_EQ(source.status().droppedFrames, 1u);
}

// OpenCV decodes a JPEG cut short with a warning only: the source refuses it.
TEST(ImageBoardSource, RefusesAJpegCutShort)
{
	SKIP_WITHOUT_IMAGE_CODECS();
	Harness h;
	cv::Mat mat(24, 32, CV_8UC3, cv::Scalar(10, 20, 30));
	std::vector<uchar> jpeg;
	cv::imencode(".jpg", mat, jpeg);
	std::string path = h.dir + "/board.jpg";
	replaceByRename(path, jpeg);
	BoardSettings settings;
	settings.image = path;
	ImageBoardSource source(settings);
	DeviceStatus cut;
	h.steps.push_back([&] { writeBytes(path, jpeg, jpeg.size() * 2 / 3); });
	h.steps.push_back([&] { cut = source.status(); });
	h.run(source);
	EXPECT_EQ(h.pictures.size(), 1u);
	EXPECT_EQ(cut.state, DeviceState::Lost);
	EXPECT_NE(cut.detail.find("cut short"), std::string::npos) << cut.detail;
}

TEST(ImageBoardSource, AMissingFileIsLostUntilItAppears)
{
	SKIP_WITHOUT_IMAGE_CODECS();
	Harness h;
	BoardSettings settings;
	settings.image = h.path;
	ImageBoardSource source(settings);
	DeviceState before = DeviceState::Stopped;
	h.steps.push_back([&] { before = source.status().state; replaceByRename(h.path, encodePng({ 1, 2, 3 })); });
	h.steps.push_back([] {});
	h.run(source);
	EXPECT_EQ(before, DeviceState::Lost);
	ASSERT_FALSE(h.statuses.empty());
	EXPECT_EQ(h.statuses.front().error, -ENOENT);
	ASSERT_EQ(h.pictures.size(), 1u);
	EXPECT_EQ(h.pictures[0], (Rgb8{ 1, 2, 3 }));
	EXPECT_EQ(source.status().state, DeviceState::Streaming);
}

// Issue 31 point 9: the picture is decoded off the event loop, so the loop
// goes on handing frames on while a large one decodes. A 5 ms timer ticks
// through the replacement: on the loop, the longest gap between its ticks
// is far shorter than the time from the replacement to the picture's
// delivery (the decode). Decoding on the loop made that gap the whole decode.
TEST(ImageBoardSource, DecodesOffTheEventLoop)
{
	SKIP_WITHOUT_IMAGE_CODECS();
	Harness h;
	replaceByRename(h.path, encodePng({ 1, 2, 3 }));
	cv::Mat noise(2048, 2048, CV_8UC3);
	cv::randu(noise, cv::Scalar::all(0), cv::Scalar::all(256));
	noise.at<cv::Vec3b>(0, 0) = cv::Vec3b(30, 20, 10);
	std::vector<uchar> large;
	cv::imencode(".png", noise, large);
	BoardSettings settings;
	settings.image = h.path;
	ImageBoardSource source(settings);

	uint64_t replacedUs = 0, deliveredUs = 0, lastTickUs = 0, longestGapUs = 0;
	EventSource ticker, replace, timeout;
	ASSERT_EQ(source.start(
			  h.loop,
			  [&](const ColourFrame &f) {
				  h.pictures.push_back(f.rgb.at(0, 0));
				  if (h.pictures.size() == 2) {
					  deliveredUs = h.loop.nowUs();
					  longestGapUs = std::max(longestGapUs, deliveredUs - lastTickUs);
					  h.loop.exit(0);
				  }
			  },
			  [](const DeviceStatus &) {}),
		  0);
	h.loop.addPeriodic(5000, [&] {
		uint64_t now = h.loop.nowUs();
		if (replacedUs && lastTickUs)
			longestGapUs = std::max(longestGapUs, now - lastTickUs);
		lastTickUs = now;
	}, ticker);
	h.loop.addTimer(100000, [&] {
		replaceByRename(h.path, large);
		replacedUs = lastTickUs = h.loop.nowUs();
	}, replace);
	h.loop.addTimer(20'000'000, [&] { h.loop.exit(1); }, timeout);
	ASSERT_EQ(h.loop.run(), 0);
	ASSERT_EQ(h.pictures.size(), 2u);
	EXPECT_EQ(h.pictures[1], (Rgb8{ 10, 20, 30 }));
	const uint64_t decodeUs = deliveredUs - replacedUs;
	std::printf("replacement to delivery %.1f ms, longest gap between 5 ms ticks %.1f ms\n", decodeUs / 1e3,
		    longestGapUs / 1e3);
	EXPECT_LT(longestGapUs * 2, decodeUs);
}
