// Issue 30: the preview shows what is recorded. Headless Chromium (Debian's
// chromium) loads the page of a depthkeyd in the simulated board's geometry;
// every tile's image, fetched from the URL the page gives it, is compared
// with the shared-memory frame of the same capture time (X-Timestamp against
// the slot's timestamp_ns):
//   composite  the composite stream, at its size (1920x780 here);
//   lecturer   the board-geometry lecturer layer over the page's checkerboard;
//   board      the composite where that layer is transparent;
//   colour     the camera-geometry lecturer layer's colours;
//   alpha      its alpha.
// Depth and seeds have no shared-memory stream: they are checked to be shown
// at their sizes. Compared 4x reduced (area mean), so that JPEG's noise
// averages out and the frames kept stay small; the tolerances are in
// kMeanTolerance and kBlockTolerance. Skipped, and reported so, where
// chromium is not installed. DEPTHKEY_SHOTS=DIR keeps the page's screenshot.
#include "hal/depthkey_shm.h"
#include "hal/preview/stage_picture.hpp"
#include "tests/process/daemon_process.hpp"
#include "tests/process/preview_test_util.hpp"
#include "tests/process/shell_command.hpp"
#include "tests/shm_test_util.hpp"
#include "tests/test_paths.hpp"
#include "tests/wait_until.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cerrno>
#include <deque>
#include <fstream>
#include <sstream>
#include <cstdio>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <thread>

using namespace std::chrono_literals;
using depthkey::test::DaemonProcess;

namespace {

constexpr int kReduce = 4;
// Per channel, on the 4x-reduced pictures: the mean absolute difference over
// the frame, and the largest difference of a block. Measured at the page's
// JPEG quality (80): see the figures the test prints.
constexpr double kMeanTolerance = 3.0;
constexpr double kBlockTolerance = 40.0;

struct TimedJpeg {
	uint64_t timestampUs = 0;
	std::string jpeg;
};

cv::Mat reduce(const cv::Mat &image)
{
	cv::Mat out;
	cv::resize(image, out, cv::Size(image.cols / kReduce, image.rows / kReduce), 0, 0, cv::INTER_AREA);
	return out;
}

// What each stream's frame should look like on the page, 4x reduced, BGR or grey.
struct Expected {
	int width = 0, height = 0;
	cv::Mat picture;   // the tile's picture
	cv::Mat valid;     // blocks compared (255); empty: all
};

// The page's checkerboard under a straight-alpha RGBA layer, in floating point, as BGR.
cv::Mat overCheckerboard(const cv::Mat &rgba)
{
	cv::Mat over(rgba.size(), CV_8UC3);
	for (int y = 0; y < rgba.rows; y++)
		for (int x = 0; x < rgba.cols; x++) {
			const cv::Vec4b p = rgba.at<cv::Vec4b>(y, x);
			const double a = p[3] / 255.0;
			const double k = ((x / depthkey::kCheckerSquare + y / depthkey::kCheckerSquare) & 1)
						 ? depthkey::kCheckerDark
						 : depthkey::kCheckerLight;
			for (int c = 0; c < 3; c++) // RGBA to BGR
				over.at<cv::Vec3b>(y, x)[2 - c] = cv::saturate_cast<uint8_t>(p[c] * a + k * (1.0 - a));
		}
	return over;
}

// Reads the three streams' newest frames while the test runs and keeps the
// last kKept of each by capture time (µs), to be compared with the tiles
// fetched meanwhile.
class SharedMemoryFrames
{
public:
	static constexpr size_t kKept = 24;

	explicit SharedMemoryFrames(const std::string &prefix) : prefix_(prefix) {}
	~SharedMemoryFrames() { stop(); }
	void start() { thread_ = std::thread([this] { run(); }); }
	void stop()
	{
		stop_ = true;
		if (thread_.joinable())
			thread_.join();
	}
	// What the tile ("composite", "lecturer", "board", "colour" or
	// "alpha") should show for the frame captured at timestampUs.
	bool expected(const std::string &tile, uint64_t timestampUs, Expected &out)
	{
		cv::Mat composite, layer, lecturer;
		{
			std::lock_guard lock(mutex_);
			composite = frame(".composite", timestampUs);
			layer = frame(".lecturer.board", timestampUs);
			lecturer = frame(".lecturer", timestampUs);
		}
		if (tile == "composite" && !composite.empty()) {
			cv::Mat bgr;
			cv::cvtColor(composite, bgr, cv::COLOR_RGB2BGR);
			out = { bgr.cols, bgr.rows, reduce(bgr), {} };
		} else if (tile == "lecturer" && !layer.empty()) {
			out = { layer.cols, layer.rows, reduce(overCheckerboard(layer)), {} };
		} else if (tile == "board" && !composite.empty() && !layer.empty()) {
			// The composite where the layer is transparent in a block and
			// its neighbours (JPEG's 8x8 blocks): the board's picture alone.
			cv::Mat bgr, alpha, some, blocks;
			cv::cvtColor(composite, bgr, cv::COLOR_RGB2BGR);
			cv::extractChannel(layer, alpha, 3);
			cv::dilate(alpha > 0, some, cv::Mat::ones(2 * kReduce + 9, 2 * kReduce + 9, CV_8U));
			const cv::Mat reduced = reduce(bgr);
			cv::resize(some, blocks, reduced.size(), 0, 0, cv::INTER_AREA);
			out = { bgr.cols, bgr.rows, reduced, blocks == 0 };
		} else if ((tile == "colour" || tile == "alpha") && !lecturer.empty()) {
			cv::Mat picture;
			if (tile == "colour")
				cv::cvtColor(lecturer, picture, cv::COLOR_RGBA2BGR);
			else
				cv::extractChannel(lecturer, picture, 3);
			out = { picture.cols, picture.rows, reduce(picture), {} };
		} else {
			return false;
		}
		return true;
	}
	size_t count()
	{
		std::lock_guard lock(mutex_);
		return frames_.size();
	}
	// The capture times kept of a stream, oldest first (for a failure's message).
	std::string times(const std::string &suffix)
	{
		std::lock_guard lock(mutex_);
		std::string text;
		for (const auto &[key, image] : frames_)
			if (key.first == suffix)
				text += std::to_string(key.second) + " ";
		return text;
	}

private:
	struct Stream {
		std::string suffix;
		dk_shm_reader reader{};
		bool open = false;
		std::vector<uint8_t> buffer;
		uint64_t lastTimestamp = 0;
		std::deque<uint64_t> kept;
	};

	cv::Mat frame(const std::string &suffix, uint64_t timestampUs)
	{
		auto it = frames_.find({ suffix, timestampUs });
		return it == frames_.end() ? cv::Mat() : it->second;
	}

	void read(Stream &s)
	{
		if (!s.open && dk_shm_open((prefix_ + s.suffix).c_str(), &s.reader) == 0)
			s.open = true;
		if (!s.open)
			return;
		s.buffer.resize(s.reader.frame_bytes);
		dk_shm_frame_info info{};
		const int ret = dk_shm_read_latest(&s.reader, s.buffer.data(), s.buffer.size(), &info);
		if (ret == -ESTALE) { // the daemon re-opened its streams: open them again
			dk_shm_close(&s.reader);
			s.open = false;
		}
		if (ret != 0) {
			errors_[ret]++;
			return;
		}
		if (info.timestamp_ns == s.lastTimestamp)
			return;
		s.lastTimestamp = info.timestamp_ns;
		const int type = dk_shm_bytes_per_pixel(info.fourcc) == 4 ? CV_8UC4 : CV_8UC3;
		const cv::Mat image(int(info.height), int(info.width), type, s.buffer.data(), info.stride);
		std::lock_guard lock(mutex_);
		frames_[{ s.suffix, info.timestamp_ns / 1000 }] = image.clone();
		s.kept.push_back(info.timestamp_ns / 1000);
		if (s.kept.size() > kKept) {
			frames_.erase({ s.suffix, s.kept.front() });
			s.kept.pop_front();
		}
	}

	void run()
	{
		Stream streams[3];
		streams[0].suffix = ".composite";
		streams[1].suffix = ".lecturer";
		streams[2].suffix = ".lecturer.board";
		while (!stop_) {
			for (Stream &s : streams)
				read(s);
			std::this_thread::sleep_for(2ms);
		}
		for (Stream &s : streams)
			if (s.open)
				dk_shm_close(&s.reader);
	}

	std::string prefix_;
	std::thread thread_;
	std::atomic<bool> stop_{ false };
	std::mutex mutex_;
	std::map<std::pair<std::string, uint64_t>, cv::Mat> frames_;
public:
	std::map<int, int> errors_; // read after stop()
};

// One GET as the page's <img> makes it: the JPEG and its X-Timestamp.
TimedJpeg fetchTimed(const std::string &url)
{
	static std::atomic<int> counter{ 0 };
	const std::string base = "/tmp/depthkey-tile-" + std::to_string(getpid()) + "-" + std::to_string(counter++);
	int status = 0;
	depthkey::test::run("curl -s --max-time 5 -D " + base + ".head -o " + base + ".jpg '" + url + "'", status);
	TimedJpeg out;
	std::ifstream head(base + ".head"), body(base + ".jpg", std::ios::binary);
	std::string line;
	while (std::getline(head, line))
		if (line.rfind("X-Timestamp: ", 0) == 0)
			out.timestampUs = std::stoull(line.substr(13));
	std::stringstream bytes;
	bytes << body.rdbuf();
	out.jpeg = bytes.str();
	unlink((base + ".head").c_str());
	unlink((base + ".jpg").c_str());
	return out;
}

// The URLs the page's script fetches each tile's JPEG from (data-src, to
// which it adds ?n=N), from Chromium's DOM.
std::map<std::string, std::string> tileSources(const std::string &dom)
{
	std::map<std::string, std::string> sources;
	size_t at = 0;
	while ((at = dom.find("<img id=\"img-", at)) != std::string::npos) {
		const size_t idEnd = dom.find('"', at + 13);
		const size_t src = dom.find("data-src=\"", idEnd);
		const size_t srcEnd = dom.find('"', src + 10);
		if (idEnd == std::string::npos || src == std::string::npos || srcEnd == std::string::npos)
			break;
		sources[dom.substr(at + 13, idEnd - at - 13)] = dom.substr(src + 10, srcEnd - src - 10);
		at = srcEnd;
	}
	return sources;
}

} // namespace

TEST(PreviewTiles, EveryTileShowsTheSharedMemorysFrame)
{
	if (!depthkey::test::chromiumInstalled())
		GTEST_SKIP() << "chromium is not installed: the tile test is skipped";
	int status = 0;

	DaemonProcess daemon;
	// The simulator calibrated as make run calibrates it: board geometry.
	const std::string calibration = daemon.writeFile("calibration.toml", "");
	ASSERT_EQ(std::system((depthkey::test::binDir() + "/depthkey-calibrate --sim --output " + calibration +
			       " >/dev/null 2>&1").c_str()),
		  0);
	const std::string prefix = "/depthkey-tiles-" + std::to_string(getpid());
	const std::string config = daemon.writeFile(
		"depthkey.toml", "[colour]\nwidth = 640\nheight = 480\nfps = 25\n[mapping]\ncalibration_file = \"" +
					 calibration + "\"\n[output]\ncomposite_name = \"" + prefix +
					 ".composite\"\nlecturer_name = \"" + prefix + ".lecturer\"\nboard_lecturer_name = \"" +
					 prefix + ".lecturer.board\"\nslots = 8\n[preview]\nlisten = \"127.0.0.1:0\"\n");
	ASSERT_TRUE(daemon.start({ "--config", config }));
	ASSERT_TRUE(daemon.waitForNotify("READY=1", 20s)) << daemon.log();
	const std::string url = depthkey::test::previewUrlFromLog(daemon.log());
	ASSERT_FALSE(url.empty()) << daemon.log();

	// The board source starts after READY=1 and the composite goes to the
	// board's geometry with its first picture; on a loaded machine (CI) the
	// page was read before either. The page is read once status.json says both.
	nlohmann::json board;
	depthkey::test::waitUntil(
		[&] {
			const depthkey::test::HttpReply reply = depthkey::test::curlGet(url + "/status.json");
			if (reply.code != 200)
				return false;
			const nlohmann::json j = nlohmann::json::parse(reply.body, nullptr, false);
			if (!j.is_object() || !j.contains("board"))
				return false;
			board = j["board"];
			return board.is_object() && board.value("state", "") == "streaming" && board.value("geometry", false);
		},
		20s, 200ms);
	std::printf("    status.json's board before the page was read: %s\n", board.dump().c_str());
	// The page as Chromium runs it: its script has filled the status table
	// and every tile has its source.
	const char *shots = std::getenv("DEPTHKEY_SHOTS");
	const std::string shot = (shots ? std::string(shots) : daemon.dir()) + "/preview-page.png";
	const std::string chromium = depthkey::test::headlessChromium("1280,1600");
	std::string dom = depthkey::test::run(chromium + "--dump-dom " + url + "/ 2>/dev/null", status);
	ASSERT_EQ(status, 0) << dom;
	// The daemon's STATUS= datagrams are drained between the steps: a
	// notify socket's queue (net.unix.max_dgram_qlen, 10) full makes
	// sd_notify, and so the daemon's loop, wait.
	daemon.pollNotify();
	depthkey::test::run(chromium + "--screenshot=" + shot + " " + url + "/ 2>&1", status);
	daemon.pollNotify();
	std::printf("    page screenshot: %s\n", shot.c_str());
	for (const char *row : { ">board (sim-board)<", ">depth offset (", ">depth arrival (after its capture stamp)<",
				 ">keying<", ">version<", ">config<", ">readers<" })
		EXPECT_NE(dom.find(row), std::string::npos) << "no status row " << row << " in the page";
	EXPECT_NE(dom.find("(board geometry 1920x"), std::string::npos) << "the composite's caption names its geometry";
	const std::map<std::string, std::string> sources = tileSources(dom);
	for (const char *tile : { "composite", "lecturer", "board", "colour", "depth", "seeds", "alpha" })
		EXPECT_EQ(sources.count(tile), 1u) << "the page has no " << tile << " tile";

	// Each tile's stream, fetched as the page fetches it, beside the shared memory.
	SharedMemoryFrames frames(prefix);
	frames.start();
	std::this_thread::sleep_for(300ms);
	// Each tile's picture fetched as its <img> fetches it, several times,
	// each set beside the shared memory's frame of its capture time at once
	// (the frames are kept only a second or so).
	struct Fetched {
		TimedJpeg jpeg;
		bool haveExpected = false;
		Expected expected;
	};
	// One client, the tiles in turn (a loaded 2-core box keys a few frames
	// a second; seven clients at once starved the shared-memory reader).
	// Until two of each tile met their frame: on a loaded box the reader
	// misses frames (it copies only the newest), so a picture may find none.
	std::map<std::string, std::vector<Fetched>> parts;
	std::map<std::string, int> met;
	for (int round = 0; round < 12; round++)
		for (const auto &[tile, src] : sources) {
			if (met[tile] >= 2 || (round >= 2 && (tile == "depth" || tile == "seeds")))
				continue;
			Fetched f;
			f.jpeg = fetchTimed(url + src);
			daemon.pollNotify();
			// A JPEG (not a 503's text: no frame within 3 s on a loaded box).
			if (f.jpeg.jpeg.size() < 2 || uint8_t(f.jpeg.jpeg[0]) != 0xff || uint8_t(f.jpeg.jpeg[1]) != 0xd8)
				continue;
			// The preview is offered the frame just before it is published:
			// its JPEG may come before the reader has the frame.
			for (int wait = 0; wait < 25; wait++) {
				f.haveExpected = frames.expected(tile, f.jpeg.timestampUs, f.expected);
				if (f.haveExpected)
					break;
				std::this_thread::sleep_for(20ms);
			}
			met[tile] += f.haveExpected;
			parts[tile].push_back(std::move(f));
		}
	std::printf("    shared-memory frames kept: %zu; composite capture times (us) kept: %s\n", frames.count(),
		    frames.times(".composite").c_str());
	frames.stop();
	for (const auto &[ret, n] : frames.errors_)
		std::printf("    shared-memory reads that returned %d: %d\n", ret, n);

	for (const auto &[tile, src] : sources) {
		const std::vector<Fetched> &got = parts[tile];
		ASSERT_FALSE(got.empty()) << tile << ": no picture from " << src << "; the daemon's log:\n" << daemon.log();
		const bool grey = tile == "alpha";
		if (tile == "depth" || tile == "seeds") {
			// No shared-memory stream: shown, at the ToF's size enlarged 4x
			// (depth) or the colour camera's (seeds).
			const std::string &jpeg = got[0].jpeg.jpeg;
			cv::Mat image = cv::imdecode(cv::Mat(1, int(jpeg.size()), CV_8U, (void *)jpeg.data()), cv::IMREAD_COLOR);
			ASSERT_FALSE(image.empty()) << tile;
			EXPECT_GE(image.cols, 320) << tile;
			continue;
		}
		int matched = 0;
		double worstMean = 0, worstBlock = 0;
		std::string fetchedTimes;
		for (const Fetched &f : got)
			fetchedTimes += std::to_string(f.jpeg.timestampUs) + " ";
		for (const Fetched &f : got) {
			if (!f.haveExpected)
				continue;
			const TimedJpeg &part = f.jpeg;
			const Expected &expected = f.expected;
			cv::Mat image = cv::imdecode(cv::Mat(1, int(part.jpeg.size()), CV_8U, (void *)part.jpeg.data()),
						     grey ? cv::IMREAD_GRAYSCALE : cv::IMREAD_COLOR);
			ASSERT_FALSE(image.empty()) << tile;
			ASSERT_EQ(image.cols, expected.width) << tile << ": not the recorded size";
			ASSERT_EQ(image.rows, expected.height) << tile << ": not the recorded size";
			cv::Mat difference;
			cv::absdiff(reduce(image), expected.picture, difference);
			const cv::Mat mask =
				expected.valid.empty() ? cv::Mat(difference.size(), CV_8U, cv::Scalar(255)) : expected.valid;
			ASSERT_GT(cv::countNonZero(mask), int(mask.total() / 10)) << tile << ": too few blocks to compare";
			// Per channel: the mean over the compared blocks, and the largest.
			std::vector<cv::Mat> planes;
			cv::split(difference, planes);
			double meanDifference = 0, maxDifference = 0;
			for (const cv::Mat &plane : planes) {
				double largest = 0;
				cv::minMaxLoc(plane, nullptr, &largest, nullptr, nullptr, mask);
				maxDifference = std::max(maxDifference, largest);
				meanDifference += cv::mean(plane, mask)[0] / double(planes.size());
			}
			worstMean = std::max(worstMean, meanDifference);
			worstBlock = std::max(worstBlock, maxDifference);
			matched++;
		}
		std::printf("    %-9s %zu pictures, %d matched by capture time: mean difference <= %.2f, block <= %.0f\n",
			    tile.c_str(), got.size(), matched, worstMean, worstBlock);
		EXPECT_GT(matched, 0) << tile << ": no picture had a shared-memory frame of its capture time (pictures at "
				      << fetchedTimes << "us)";
		EXPECT_LE(worstMean, kMeanTolerance) << tile;
		EXPECT_LE(worstBlock, kBlockTolerance) << tile;
	}
	depthkey::test::unlinkStreams(prefix);
	shm_unlink((prefix + ".lecturer.board").c_str());
}
