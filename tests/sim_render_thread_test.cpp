// The simulated cameras render on threads of their own (issue 29 §2: the
// simulator's rendering is not the box's cost and stays out of the CPU
// share): each frame is rendered off the event loop's thread and delivered
// on it, a render slower than the period drops the ticks it overruns (and
// counts them, as a real camera drops frames the host is too slow for), and
// a stop while a frame renders waits for it and delivers nothing.
#include "hal/board/board_sources.hpp"
#include "hal/event_loop.hpp"
#include "hal/sim/sim_cameras.hpp"
#include "tests/wait_until.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <dirent.h>
#include <fstream>
#include <set>
#include <string>
#include <thread>
#include <vector>

using namespace depthkey;

namespace {

// A simulated camera whose "scene" is a render of a set length that records
// where it ran.
class TimedRenderCamera final : public PeriodicSimCamera<ColourFrame>
{
public:
	TimedRenderCamera(int fps, std::chrono::milliseconds renderTime) : fps_(fps), renderTime_(renderTime) {}
	~TimedRenderCamera() override { stop(); }
	std::string name() const override { return "timed-render"; }

	std::atomic<int> renders{ 0 }, finished{ 0 };
	std::atomic<bool> renderedOnCallerThread{ false };
	std::thread::id callerThread = std::this_thread::get_id();

private:
	const char *threadName() const override { return "dk-sim-test"; }
	int fps() const override { return fps_; }
	void prepare() override {}
	void render(uint64_t, ColourFrame &frame) override
	{
		renders++;
		if (std::this_thread::get_id() == callerThread)
			renderedOnCallerThread = true;
		frame.rgb.resize(8, 8);
		// Each frame its own colour: its number (frame.sequence is the last one's).
		const uint8_t shade = uint8_t(frame.sequence + 1);
		std::fill(frame.rgb.data(), frame.rgb.data() + frame.rgb.size(), Rgb8{ shade, shade, shade });
		std::this_thread::sleep_for(renderTime_);
		finished++;
	}

	int fps_;
	std::chrono::milliseconds renderTime_;
};

// The names of this process's threads (/proc/self/task/*/comm).
std::multiset<std::string> threadNames()
{
	std::multiset<std::string> names;
	DIR *dir = opendir("/proc/self/task");
	if (!dir)
		return names;
	while (dirent *entry = readdir(dir)) {
		if (entry->d_name[0] == '.')
			continue;
		std::ifstream comm(std::string("/proc/self/task/") + entry->d_name + "/comm");
		std::string name;
		if (std::getline(comm, name))
			names.insert(name);
	}
	closedir(dir);
	return names;
}

// Runs the loop until a handler exits it (0), or 5 s pass (1).
int runUntilExit(EventLoop &loop)
{
	EventSource timeout;
	if (loop.addTimer(5'000'000, [&] { loop.exit(1); }, timeout) < 0)
		return -1;
	return loop.run();
}

void runFor(EventLoop &loop, uint64_t us)
{
	EventSource timeout;
	ASSERT_EQ(loop.addTimer(us, [&] { loop.exit(0); }, timeout), 0);
	ASSERT_EQ(loop.run(), 0);
}

} // namespace

TEST(SimRenderThread, FramesAreRenderedOffTheLoopAndDeliveredOnItAfterTheirRender)
{
	EventLoop loop;
	ASSERT_EQ(loop.open(), 0);
	TimedRenderCamera camera(50, std::chrono::milliseconds(5));
	std::vector<uint64_t> sequences;
	bool deliveredOffLoop = false;
	uint64_t shortestDelayUs = ~0ull;
	ASSERT_EQ(camera.start(
			  loop,
			  [&](const ColourFrame &f) {
				  if (std::this_thread::get_id() != camera.callerThread)
					  deliveredOffLoop = true;
				  shortestDelayUs = std::min(shortestDelayUs, loop.nowUs() - f.timestampNs / 1000u);
				  sequences.push_back(f.sequence);
				  if (sequences.size() == 5)
					  loop.exit(0);
			  },
			  [](const DeviceStatus &) {}),
		  0);
	EXPECT_EQ(threadNames().count("dk-sim-test"), 1u);
	ASSERT_EQ(runUntilExit(loop), 0);
	camera.stop();
	EXPECT_FALSE(camera.renderedOnCallerThread);
	EXPECT_FALSE(deliveredOffLoop);
	EXPECT_EQ(sequences, (std::vector<uint64_t>{ 1, 2, 3, 4, 5 }));
	// A frame arrives a render after its capture, as a real camera's
	// arrives a transfer after it.
	EXPECT_GE(shortestDelayUs, 5000u);
	EXPECT_EQ(threadNames().count("dk-sim-test"), 0u) << "the render thread outlived stop()";
}

// A handler may keep a pointer to the frame it was given until the next
// (daemon/board_output.hpp's waiting board picture): the next render, made
// while the loop still has it, goes into the other buffer.
TEST(SimRenderThread, ADeliveredFrameStaysAsItWasUntilTheNextIsDelivered)
{
	EventLoop loop;
	ASSERT_EQ(loop.open(), 0);
	TimedRenderCamera camera(100, std::chrono::milliseconds(2));
	const ColourFrame *last = nullptr;
	uint8_t lastShade = 0;
	int frames = 0, kept = 0;
	ASSERT_EQ(camera.start(
			  loop,
			  [&](const ColourFrame &f) {
				  if (last && last != &f && last->rgb.data()[0].r == lastShade)
					  kept++;
				  last = &f;
				  lastShade = f.rgb.data()[0].r;
				  EXPECT_EQ(lastShade, uint8_t(f.sequence));
				  if (++frames == 6)
					  loop.exit(0);
			  },
			  [](const DeviceStatus &) {}),
		  0);
	ASSERT_EQ(runUntilExit(loop), 0);
	camera.stop();
	EXPECT_EQ(kept, 5) << "a frame's buffer was rendered into before the next frame was delivered";
}

TEST(SimRenderThread, ARenderSlowerThanThePeriodDropsTheTicksItOverrunsAndCountsThem)
{
	EventLoop loop;
	ASSERT_EQ(loop.open(), 0);
	// 45 ms renders at 100 fps: each spans four ticks or more.
	TimedRenderCamera camera(100, std::chrono::milliseconds(45));
	std::vector<uint64_t> sequences;
	ASSERT_EQ(camera.start(
			  loop, [&](const ColourFrame &f) { sequences.push_back(f.sequence); }, [](const DeviceStatus &) {}),
		  0);
	runFor(loop, 500'000);
	const DeviceStatus status = camera.status();
	camera.stop();
	ASSERT_GE(sequences.size(), 2u);
	EXPECT_EQ(status.state, DeviceState::Streaming);
	// A frame is made only once the last one is in; the ticks between are
	// dropped (a loop late by more than a period merges ticks: at least
	// one each render, on the most loaded machine).
	EXPECT_GE(status.droppedFrames, sequences.size() - 1);
	EXPECT_LE(size_t(camera.renders), sequences.size() + 1);
	// Dropped ticks are frames never made: the numbers of those made run on.
	for (size_t i = 0; i < sequences.size(); i++)
		EXPECT_EQ(sequences[i], i + 1);
	EXPECT_EQ(camera.status().droppedFrames, status.droppedFrames) << "stop() keeps the count";
}

TEST(SimRenderThread, AStopWhileAFrameRendersWaitsForItDeliversNothingAndARestartStreamsAgain)
{
	EventLoop loop;
	ASSERT_EQ(loop.open(), 0);
	TimedRenderCamera camera(100, std::chrono::milliseconds(60));
	std::vector<uint64_t> sequences;
	auto onFrame = [&](const ColourFrame &f) { sequences.push_back(f.sequence); };
	auto ignore = [](const DeviceStatus &) {};
	ASSERT_EQ(camera.start(loop, onFrame, ignore), 0);
	// Stopped as soon as the first render has begun; 150 ms later (what
	// was rendered across the stop would have come by then) started again.
	int finishedAtStop = -1, rendersWhileStopped = -1;
	size_t deliveredWhileStopped = ~size_t(0);
	DeviceState stateAtStop = DeviceState::Streaming;
	EventSource poll, restart, end;
	ASSERT_EQ(loop.addPeriodic(
			  1000,
			  [&] {
				  if (camera.renders == 0)
					  return;
				  camera.stop();
				  finishedAtStop = camera.finished;
				  stateAtStop = camera.status().state;
				  poll.reset();
				  loop.addTimer(
					  150'000,
					  [&] {
						  deliveredWhileStopped = sequences.size();
						  rendersWhileStopped = camera.renders;
						  EXPECT_EQ(camera.start(loop, onFrame, ignore), 0);
						  loop.addTimer(300'000, [&] { loop.exit(0); }, end);
					  },
					  restart);
			  },
			  poll),
		  0);
	ASSERT_EQ(runUntilExit(loop), 0);
	camera.stop();
	EXPECT_EQ(finishedAtStop, 1) << "stop() returned while a render still ran";
	EXPECT_EQ(stateAtStop, DeviceState::Stopped);
	EXPECT_EQ(deliveredWhileStopped, 0u) << "a frame rendered across a stop was delivered";
	EXPECT_EQ(rendersWhileStopped, 1);
	ASSERT_FALSE(sequences.empty()) << "no frame after the restart";
	EXPECT_EQ(sequences.front(), 1u) << "a restart numbers from 1 again";
}

TEST(SimRenderThread, EachSimulatedCameraRendersOnItsOwnNamedThread)
{
	EventLoop loop;
	ASSERT_EQ(loop.open(), 0);
	ColourCameraSettings colourSettings;
	colourSettings.width = 64;
	colourSettings.height = 48;
	DepthCameraSettings depthSettings;
	BoardSettings boardSettings;
	boardSettings.width = 64;
	SimColourCamera colour(colourSettings, SimSettings{});
	SimDepthCamera depth(depthSettings, SimSettings{});
	SimBoardSource board(boardSettings, SimSettings{});
	int colourFrames = 0, depthFrames = 0, boardFrames = 0;
	auto ignore = [](const DeviceStatus &) {};
	ASSERT_EQ(colour.start(loop, [&](const ColourFrame &) { colourFrames++; }, ignore), 0);
	ASSERT_EQ(depth.start(loop, [&](const DepthFrame &) { depthFrames++; }, ignore), 0);
	ASSERT_EQ(board.start(loop, [&](const ColourFrame &) { boardFrames++; }, ignore), 0);
	const std::multiset<std::string> names = threadNames();
	EXPECT_EQ(names.count("dk-sim-colour"), 1u);
	EXPECT_EQ(names.count("dk-sim-depth"), 1u);
	EXPECT_EQ(names.count("dk-sim-board"), 1u);
	runFor(loop, 600'000);
	colour.stop();
	depth.stop();
	board.stop();
	EXPECT_GT(colourFrames, 0);
	EXPECT_GT(depthFrames, 0);
	EXPECT_GT(boardFrames, 0);
	// stop() joined them; under qemu-user the emulator's own thread can
	// stay listed a moment after the join (CI's arm64 run here, 8 December:
	// one left at once), so it has 2 s to go. Natively it is gone at once.
	size_t left = 0;
	depthkey::test::waitUntil(
		[&] {
			const std::multiset<std::string> after = threadNames();
			left = after.count("dk-sim-colour") + after.count("dk-sim-depth") + after.count("dk-sim-board");
			return left == 0;
		},
		std::chrono::milliseconds(2000));
	EXPECT_EQ(left, 0u);
}
