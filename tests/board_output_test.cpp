// The daemon's board (daemon/board_output.hpp): which geometry the output is
// in and why, the last good picture kept while the source is lost, the
// last good H kept when a new file is refused; and depthkeyd publishing the
// board-geometry composite and lecturer layer.
#include "algo/composite.hpp"
#include "daemon/board_output.hpp"
#include "daemon/daemon.hpp"
#include "hal/fake_frame_sink.hpp"
#include "tests/fake_camera.hpp"

#include <gtest/gtest.h>

#include <csignal>
#include <ctime>
#include <filesystem>
#include <fstream>

using namespace depthkey;
using depthkey::test::FakeCamera;

namespace {

constexpr int kCw = 64, kCh = 48, kBw = 128, kBh = 96;

// The camera sees the board's whole picture at half its resolution.
BoardCalibration doubling()
{
	BoardCalibration c;
	c.colourToBoard = boardScaling(kCw, kCh, kBw, kBh);
	c.colourWidth = kCw;
	c.colourHeight = kCh;
	c.boardWidth = kBw;
	c.boardHeight = kBh;
	c.date = "2026-12-01T00:00:00Z";
	c.points = 45;
	return c;
}

struct Fixture {
	std::filesystem::path dir;
	std::string homography;
	Settings settings;
	EventLoop loop;
	Pipeline pipeline;
	FakeCamera<ColourFrame> *source = nullptr;
	int geometryChanges = 0;
	std::vector<std::pair<std::string, DeviceState>> statuses;

	Fixture()
	{
		dir = std::filesystem::temp_directory_path() / ("depthkey-board-output-" + std::to_string(getpid()));
		std::filesystem::create_directories(dir);
		homography = (dir / "board.toml").string();
		std::string error;
		EXPECT_EQ(writeBoardCalibration(homography, doubling(), error), 0) << error;
		settings.colour.width = kCw;
		settings.colour.height = kCh;
		settings.board.backend = "v4l2";
		settings.board.width = kBw;
		settings.board.height = kBh;
		settings.board.homographyFile = homography;
		EXPECT_EQ(loop.open(), 0);
	}
	~Fixture() { std::filesystem::remove_all(dir); }

	void start(BoardOutput &board)
	{
		board.start(
			loop, settings,
			[this](const Settings &) {
				auto c = std::make_unique<FakeCamera<ColourFrame>>("fake-board");
				source = c.get();
				return c;
			},
			pipeline, [this](const std::string &name, const DeviceStatus &s) { statuses.emplace_back(name, s.state); },
			[this] { geometryChanges++; });
	}
	ColourFrame picture(Rgb8 colour, int w = kBw, int h = kBh)
	{
		ColourFrame f;
		f.rgb = RgbImage(w, h, colour);
		return f;
	}
};

} // namespace

TEST(BoardOutput, ComposesInBoardGeometryAndKeepsTheLastPictureWhileLost)
{
	Fixture f;
	BoardOutput board;
	f.start(board);
	ASSERT_TRUE(board.boardGeometry()) << board.statusText();
	EXPECT_EQ(board.outputWidth(), kBw);
	f.source->deliver(f.picture({ 20, 40, 60 }));

	// The lecturer fills the colour image's left half, opaque.
	RgbImage colour(kCw, kCh, Rgb8{ 250, 0, 0 });
	Gray8Image alpha(kCw, kCh, 0);
	for (int y = 0; y < kCh; ++y)
		for (int x = 0; x < kCw / 2; ++x)
			alpha.at(x, y) = 255;
	board.compose(colour, alpha, Roi{ 0, 0, kCw / 2, kCh }, 256);
	EXPECT_EQ(board.composite().at(10, 50), (Rgb8{ 250, 0, 0 }));
	EXPECT_EQ(board.composite().at(100, 50), (Rgb8{ 20, 40, 60 }));
	EXPECT_EQ(board.lecturer().at(10, 50).a, 255);
	EXPECT_EQ(board.lecturer().at(100, 50).a, 0);

	f.source->setState(DeviceState::Lost, -ENODEV, "unplugged");
	EXPECT_FALSE(board.sourceOk());
	EXPECT_NE(board.statusText().find("lost (last good picture kept)"), std::string::npos) << board.statusText();
	board.compose(colour, alpha, Roi{ 0, 0, kCw / 2, kCh }, 256);
	EXPECT_EQ(board.composite().at(100, 50), (Rgb8{ 20, 40, 60 })) << "the last good picture stays";
	ASSERT_FALSE(f.statuses.empty());
	EXPECT_EQ(f.statuses.back(), (std::pair<std::string, DeviceState>{ "fake-board", DeviceState::Lost }));
}

// A picture made in the daemon's lent storage waits there while keying
// runs; the next picture must not be made over it (the simulated board
// renders on a thread of its own): nothing is lent until it is taken.
TEST(BoardOutput, APictureWaitingInLentStorageIsNotLentAgain)
{
	Fixture f;
	BoardOutput board;
	bool busy = false;
	board.setPipelineBusy([&] { return busy; });
	f.start(board);
	ASSERT_TRUE(board.boardGeometry()) << board.statusText();
	ColourFrame *lent = f.source->borrow();
	ASSERT_NE(lent, nullptr);
	lent->rgb = RgbImage(kBw, kBh, Rgb8{ 9, 8, 7 });
	busy = true;
	f.source->deliver(*lent);
	EXPECT_EQ(f.source->borrow(), nullptr) << "the waiting picture would be written over";
	busy = false;
	board.takeWaitingPicture();
	EXPECT_NE(f.source->borrow(), nullptr) << "taken: storage is lent again";
	RgbImage colour(kCw, kCh, Rgb8{ 0, 0, 0 });
	board.compose(colour, Gray8Image(kCw, kCh, 0), Roi{ 0, 0, kCw, kCh }, 256);
	EXPECT_EQ(board.composite().at(100, 50), (Rgb8{ 9, 8, 7 }));
}

TEST(BoardOutput, SaysWhyItIsNotCalibratedAndFallsBackToCameraGeometry)
{
	Fixture f;
	f.settings.board.homographyFile = "";
	BoardOutput board;
	f.start(board);
	EXPECT_FALSE(board.boardGeometry());
	EXPECT_NE(board.statusText().find("board not calibrated (board.homography_file is empty"), std::string::npos)
		<< board.statusText();

	// Calibrated, then the stick delivers another resolution: camera geometry, and why.
	f.settings.board.homographyFile = f.homography;
	board.apply(f.settings);
	ASSERT_TRUE(board.boardGeometry());
	int changes = f.geometryChanges;
	f.source->deliver(f.picture({ 1, 2, 3 }, 100, 50));
	EXPECT_FALSE(board.boardGeometry());
	EXPECT_GT(f.geometryChanges, changes) << "the output streams must be re-opened";
	EXPECT_NE(board.statusText().find("calibrated for a board picture of 128x96, the source gives 100x50"),
		  std::string::npos)
		<< board.statusText();
}

TEST(BoardOutput, ARefusedFileKeepsTheLastGoodHomographyAndOutputSizeScales)
{
	Fixture f;
	f.settings.board.outputWidth = 256;
	f.settings.board.outputHeight = 192;
	BoardOutput board;
	f.start(board);
	ASSERT_TRUE(board.boardGeometry());
	EXPECT_EQ(board.outputWidth(), 256);
	std::ofstream(f.homography) << "format = 1\n[board]\nhomography = [1, 2\n"; // cut short
	board.apply(f.settings);
	EXPECT_TRUE(board.boardGeometry()) << board.statusText();
	f.source->deliver(f.picture({ 9, 9, 9 }));
	board.showBoardOnly();
	EXPECT_EQ(board.composite().at(255, 191), (Rgb8{ 9, 9, 9 }));
}

namespace {

void unblockSignals()
{
	sigset_t set;
	sigfillset(&set);
	sigprocmask(SIG_UNBLOCK, &set, nullptr);
}

uint64_t monotonicNs()
{
	timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return uint64_t(ts.tv_sec) * 1000000000u + uint64_t(ts.tv_nsec);
}

} // namespace

// depthkeyd in board geometry: the composite stream is the board's size,
// the board-geometry layer is published beside the camera-geometry one.
TEST(BoardOutput, TheDaemonPublishesTheBoardGeometryStreams)
{
	Fixture f;
	f.settings.colour.fps = 50;
	f.settings.pairing.delayMs = 0; // each frame out as it comes: the test reads it at once
	FakeCamera<ColourFrame> *colour = nullptr, *boardSource = nullptr;
	FakeCamera<DepthFrame> *depth = nullptr;
	FakeFrameSink *sink = nullptr;
	DeviceFactory factory;
	factory.colourCamera = [&](const Settings &) {
		auto c = std::make_unique<FakeCamera<ColourFrame>>("fake-colour");
		colour = c.get();
		return c;
	};
	factory.depthCamera = [&](const Settings &) {
		auto d = std::make_unique<FakeCamera<DepthFrame>>("fake-depth");
		depth = d.get();
		return d;
	};
	factory.boardSource = [&](const Settings &) {
		auto b = std::make_unique<FakeCamera<ColourFrame>>("fake-board");
		boardSource = b.get();
		return b;
	};
	factory.frameSink = [&](const Settings &) {
		auto s = std::make_unique<FakeFrameSink>();
		sink = s.get();
		return s;
	};
	Daemon daemon("unused.toml", {}, factory);
	ASSERT_EQ(daemon.start(f.settings), 0);
	ASSERT_NE(boardSource, nullptr);
	EXPECT_EQ(sink->boardWidth(), kBw);
	boardSource->deliver(f.picture({ 30, 30, 90 }));

	ColourFrame frame;
	frame.rgb = RgbImage(kCw, kCh, Rgb8{ 10, 200, 10 });
	DepthFrame d;
	d.depthMm = Gray16Image(16, 12, 1000); // lecturer everywhere
	d.amplitude = Gray16Image(16, 12, 5000);
	d.intensity = Gray16Image(16, 12, 5000);
	EventSource timer;
	int steps = 0;
	daemon.loop().addPeriodic(20000, [&] {
		if (steps++ == 5)
			return daemon.loop().exit(0);
		d.timestampNs = frame.timestampNs = monotonicNs();
		depth->deliver(d);
		colour->deliver(frame);
	}, timer);
	daemon.run();
	unblockSignals();

	EXPECT_EQ(sink->composite().width(), kBw);
	EXPECT_EQ(sink->boardLecturer().width(), kBw);
	EXPECT_EQ(sink->lecturer().width(), kCw);
	EXPECT_GE(sink->boardLecturerCount(), 4u);
	// Nothing on the loop reads the board's images: the keyed frames are
	// made where they go (issue 29 §2); a board-only one may come first.
	EXPECT_GE(sink->boardInPlaceCount(), 4u);
	// Lecturer everywhere at opacity 0.5 over the board's own picture.
	Rgb8 mid = sink->composite().at(kBw / 2, kBh / 2);
	EXPECT_NEAR(mid.g, (200 + 30) / 2, 2);
	EXPECT_NEAR(mid.b, (10 + 90) / 2, 2);
}

// The calibration file's [board] (depthkey-calibrate --sim writes one) is the
// H while board.homography_file is empty; a board file of its own wins.
TEST(BoardOutput, TheCalibrationFilesBoardIsUsedWhileNoBoardFileIsSet)
{
	Fixture f;
	f.settings.board.homographyFile = "";
	BoardCalibration fromCalibration = doubling();
	fromCalibration.boardWidth = 2 * kBw; // told apart from the board file's by its picture size
	fromCalibration.boardHeight = 2 * kBh;
	fromCalibration.colourToBoard = boardScaling(kCw, kCh, 2 * kBw, 2 * kBh);
	BoardOutput board;
	board.setCalibrationFileBoard(fromCalibration);
	f.settings.board.width = 2 * kBw;
	f.settings.board.height = 2 * kBh;
	f.start(board);
	ASSERT_TRUE(board.boardGeometry()) << board.statusText();
	EXPECT_EQ(board.outputWidth(), 2 * kBw);

	// The pipeline is handed the picture and H: the board model learns
	// what the picture predicts (algo/board_picture_prior.hpp).
	f.source->deliver(f.picture({ 5, 6, 7 }, 2 * kBw, 2 * kBh));
	EXPECT_TRUE(f.pipeline.hasBoardPicture());

	// A board file of its own takes precedence: it is fitted for kBw x kBh.
	f.settings.board.homographyFile = f.homography;
	board.apply(f.settings);
	EXPECT_FALSE(board.boardGeometry());
	EXPECT_NE(board.statusText().find("calibrated for a board picture of 128x96"), std::string::npos)
		<< board.statusText();
	EXPECT_FALSE(f.pipeline.hasBoardPicture()) << "no picture prior without a usable H";

	// Without either: not calibrated, and the status says where it looked.
	f.settings.board.homographyFile = "";
	board.setCalibrationFileBoard(std::nullopt);
	board.apply(f.settings);
	EXPECT_FALSE(board.boardGeometry());
	EXPECT_NE(board.statusText().find("the calibration file has no [board]"), std::string::npos)
		<< board.statusText();
}
