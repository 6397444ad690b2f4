// The daemon's behaviour when a camera goes away, with fake cameras driven
// from the daemon's own event loop: the recorder keeps getting frames, marked
// offline, and the picture comes back when the camera does.
#include "daemon/daemon.hpp"
#include "hal/depthkey_shm.h"
#include "hal/fake_frame_sink.hpp"
#include "tests/fake_camera.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <csignal>
#include <ctime>
#include <unistd.h>
#include <functional>
#include <vector>

using namespace depthkey;
using depthkey::test::FakeCamera;

namespace {

uint64_t monotonicNs()
{
	timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return static_cast<uint64_t>(ts.tv_sec) * 1000000000u + static_cast<uint64_t>(ts.tv_nsec);
}

// Daemon::start blocks the signals it handles; give them back to the test binary.
void unblockSignals()
{
	sigset_t set;
	sigfillset(&set);
	sigprocmask(SIG_UNBLOCK, &set, nullptr);
}

struct Harness {
	FakeCamera<ColourFrame> *colour = nullptr;
	FakeCamera<DepthFrame> *depth = nullptr;
	FakeFrameSink *sink = nullptr;

	DeviceFactory factory()
	{
		DeviceFactory f;
		f.colourCamera = [this](const Settings &) {
			auto c = std::make_unique<FakeCamera<ColourFrame>>("fake-colour");
			colour = c.get();
			return c;
		};
		f.depthCamera = [this](const Settings &) {
			auto d = std::make_unique<FakeCamera<DepthFrame>>("fake-depth");
			depth = d.get();
			return d;
		};
		f.frameSink = [this](const Settings &) {
			auto s = std::make_unique<FakeFrameSink>();
			sink = s.get();
			return s;
		};
		return f;
	}
};

// A timeline of steps run on the daemon's loop, one every `stepUs`.
class Script
{
public:
	Script(Daemon &daemon, uint64_t stepUs) : daemon_(daemon), stepUs_(stepUs) {}
	void then(std::function<void()> step) { steps_.push_back(std::move(step)); }
	// A step that waits, up to `maxSteps` steps, for `ready`: a timer of the
	// daemon's that is due can fire late on a loaded machine (a unit run at
	// load 18 saw a 60 ms delay's frame leave after the script's 80 ms).
	void thenWhen(std::function<bool()> ready, std::function<void()> step, size_t maxSteps = 100)
	{
		ready_.resize(steps_.size());
		ready_.push_back({ std::move(ready), maxSteps });
		steps_.push_back(std::move(step));
	}
	void run()
	{
		daemon_.loop().addPeriodic(stepUs_, [this] {
			if (next_ < steps_.size()) {
				if (next_ < ready_.size() && ready_[next_].ready && !ready_[next_].ready() &&
				    ++waited_ < ready_[next_].maxSteps)
					return;
				waited_ = 0;
				steps_[next_++]();
			} else
				daemon_.loop().exit(0);
		}, timer_);
		daemon_.run();
	}

private:
	Daemon &daemon_;
	uint64_t stepUs_;
	std::vector<std::function<void()>> steps_;
	struct Gate {
		std::function<bool()> ready;
		size_t maxSteps = 0;
	};
	std::vector<Gate> ready_;
	size_t next_ = 0, waited_ = 0;
	EventSource timer_;
};

// A 32x24 colour camera at 50 fps, keyed as each frame comes (no pairing
// delay), the preview on an ephemeral loopback port.
Settings smallFastSettings()
{
	Settings settings;
	settings.colour.width = 32;
	settings.colour.height = 24;
	settings.colour.fps = 50;
	settings.pairing.delayMs = 0;
	settings.preview.listen = "127.0.0.1:0";
	return settings;
}

// One colour and one depth frame, delivered together stamped now.
struct BothCameras {
	explicit BothCameras(Harness &harness) : h(harness)
	{
		colour.rgb = RgbImage(32, 24, Rgb8{ 1, 2, 3 });
		depth.depthMm = Gray16Image(8, 6, 1000);
		depth.amplitude = Gray16Image(8, 6, 5000);
		depth.intensity = Gray16Image(8, 6, 5000);
	}
	void deliver()
	{
		depth.timestampNs = colour.timestampNs = monotonicNs();
		h.depth->deliver(depth);
		h.colour->deliver(colour);
	}
	Harness &h;
	ColourFrame colour;
	DepthFrame depth;
};

} // namespace

TEST(DaemonDegraded, PublishesOfflineFramesWhileACameraIsLostAndRecovers)
{
	Harness h;
	Settings settings;
	settings.colour.width = 64;
	settings.colour.height = 48;
	settings.preview.listen = "127.0.0.1:0"; // never the shared 8080 of parallel runs
	settings.colour.fps = 50;
	settings.board.backend = "colour"; // the composite below is over board.colour
	settings.pairing.delayMs = 0;      // each frame out as it comes: the steps below read it
	Daemon daemon("unused.toml", {}, h.factory());
	ASSERT_EQ(daemon.start(settings), 0);
	ASSERT_NE(h.colour, nullptr);
	ASSERT_NE(h.sink, nullptr);

	ColourFrame colour;
	colour.rgb = RgbImage(64, 48, Rgb8{ 10, 200, 10 });
	DepthFrame depth;
	depth.depthMm = Gray16Image(16, 12, 1000); // all lecturer
	depth.amplitude = Gray16Image(16, 12, 5000);
	depth.intensity = Gray16Image(16, 12, 5000);
	auto deliverBoth = [&] {
		depth.timestampNs = colour.timestampNs = monotonicNs();
		h.depth->deliver(depth);
		h.colour->deliver(colour);
	};

	uint32_t onlineFlags = 0, lostFlags = 0, recoveredFlags = 0;
	uint64_t countBeforeLoss = 0, countDuringLoss = 0;
	Rgb8 lostPixel{}, recoveredPixel{};
	Script script(daemon, 20000); // 20 ms per step; the colour fps is 50
	for (int i = 0; i < 5; ++i)
		script.then(deliverBoth);
	script.then([&] {
		onlineFlags = h.sink->lastFlags();
		countBeforeLoss = h.sink->compositeCount();
		h.colour->setState(DeviceState::Lost, -ENODEV, "unplugged");
	});
	for (int i = 0; i < 25; ++i) // 500 ms without colour frames
		script.then([] {});
	script.then([&] {
		lostFlags = h.sink->lastFlags();
		countDuringLoss = h.sink->compositeCount();
		lostPixel = h.sink->composite().at(2, 2);
		h.colour->setState(DeviceState::Streaming, 0, "");
	});
	for (int i = 0; i < 3; ++i)
		script.then(deliverBoth);
	script.then([&] {
		recoveredFlags = h.sink->lastFlags();
		recoveredPixel = h.sink->composite().at(32, 24);
	});
	script.run();
	unblockSignals();

	EXPECT_TRUE(onlineFlags & DK_SHM_FLAG_ONLINE);
	// Frames kept coming while the camera was gone (~12 at 50 fps, after the
	// 250 ms grace), and they were marked offline.
	EXPECT_GE(countDuringLoss - countBeforeLoss, 4u);
	EXPECT_FALSE(lostFlags & DK_SHM_FLAG_ONLINE);
	EXPECT_FALSE(lostFlags & DK_SHM_FLAG_COLOUR_OK);
	EXPECT_NE(lostPixel, (Rgb8{ 10, 200, 10 })) << "a NO SIGNAL frame, not the old picture";
	EXPECT_TRUE(recoveredFlags & DK_SHM_FLAG_ONLINE);
	// Lecturer everywhere at opacity 0.5: half green camera, half board colour.
	EXPECT_NEAR(recoveredPixel.g, (200 + 0x3c) / 2, 2);
}

TEST(DaemonDegraded, StaleDepthPublishesColourUnkeyedAndOffline)
{
	Harness h;
	Settings settings;
	settings.colour.width = 32;
	settings.colour.height = 24;
	settings.pairing.delayMs = 0; // keyed (here: not keyed) as it arrives
	settings.preview.listen = "127.0.0.1:0";
	Daemon daemon("unused.toml", {}, h.factory());
	ASSERT_EQ(daemon.start(settings), 0);
	ColourFrame colour;
	colour.rgb = RgbImage(32, 24, Rgb8{ 1, 2, 3 });
	uint32_t flags = 0;
	Rgb8 pixel{};
	Script script(daemon, 20000);
	script.then([&] {
		colour.timestampNs = monotonicNs();
		h.colour->deliver(colour); // no depth frame at all
	});
	script.then([&] { // keyed on the worker meanwhile, published by the loop
		flags = h.sink->lastFlags();
		pixel = h.sink->composite().at(5, 5);
	});
	script.run();
	unblockSignals();
	EXPECT_TRUE(flags & DK_SHM_FLAG_COLOUR_OK);
	EXPECT_FALSE(flags & DK_SHM_FLAG_DEPTH_OK);
	EXPECT_FALSE(flags & DK_SHM_FLAG_ONLINE);
	EXPECT_EQ(pixel, (Rgb8{ 1, 2, 3 }));
}

TEST(DaemonDegraded, WithoutDepthAHeldColourFrameLeavesAfterTheDelayWithItsTimestamp)
{
	Harness h;
	Settings settings;
	settings.colour.width = 32;
	settings.colour.height = 24;
	settings.pairing.delayMs = 60;
	// A slow colour rate: its NO SIGNAL frame (after 3 periods without
	// colour) stays out of the script's 80 ms even on a slow (sanitizer) build.
	settings.colour.fps = 5;
	Daemon daemon("unused.toml", {}, h.factory());
	ASSERT_EQ(daemon.start(settings), 0);
	ColourFrame colour;
	colour.rgb = RgbImage(32, 24, Rgb8{ 1, 2, 3 });
	size_t publishedAtOnce = 0, publishedLater = 0;
	uint64_t capturedNs = 0, publishedNs = 0;
	uint32_t flags = 0;
	Script script(daemon, 20000);
	script.then([&] {
		capturedNs = colour.timestampNs = monotonicNs();
		h.colour->deliver(colour); // no depth camera delivers: held for the delay
		publishedAtOnce = h.sink->compositeCount();
	});
	script.then([] {});
	script.then([] {});
	script.then([] {});
	// Due 60 ms after the delivery; waited for up to 2 s more on a loaded machine.
	script.thenWhen([&] { return h.sink->compositeCount() > 0; }, [&] {
		publishedLater = h.sink->compositeCount();
		publishedNs = h.sink->lastCaptureNs();
		flags = h.sink->lastFlags();
	});
	script.run();
	unblockSignals();
	EXPECT_EQ(publishedAtOnce, 0u);
	EXPECT_EQ(publishedLater, 1u) << "published after the 60 ms delay, by the timer alone";
	EXPECT_EQ(publishedNs, capturedNs) << "the colour camera's capture time, not the time it left";
	EXPECT_FALSE(flags & DK_SHM_FLAG_ONLINE);
}

// A loop held for longer than the colour grace (a starved box, a paused VM, a
// slow keying) has frames waiting unread in the cameras' queues: the frame
// tick that runs first when the loop resumes must not call that NO SIGNAL.
// The HIL suite saw it in CI (webcam-error-buffer-dropped, flags 0x0).
TEST(DaemonDegraded, AHeldLoopIsNotNoSignal)
{
	Harness h;
	Daemon daemon("unused.toml", {}, h.factory());
	ASSERT_EQ(daemon.start(smallFastSettings()), 0);
	BothCameras cameras(h);
	auto deliverBoth = [&] { cameras.deliver(); };
	uint64_t noColourBefore = 0, framesBefore = 0;
	Script script(daemon, 20000);
	for (int i = 0; i < 5; ++i)
		script.then(deliverBoth);
	script.then([&] {
		noColourBefore = h.sink->noColourCount();
		framesBefore = h.sink->compositeCount();
		usleep(700000); // the loop is held; the cameras' frames would queue
	});
	for (int i = 0; i < 5; ++i)
		script.then(deliverBoth);
	script.then([] {}); // the last frame comes back from the keying worker
	script.run();
	unblockSignals();
	EXPECT_EQ(h.sink->noColourCount(), noColourBefore) << "a NO SIGNAL frame after the loop was held";
	EXPECT_GE(h.sink->compositeCount() - framesBefore, 5u);
}

// A box that keys slower than its colour camera delivers keys on its worker
// (daemon/keying_worker.hpp) while the loop goes on turning for the depth
// camera, the LEDs and the readers: the HIL VM keyed at 180 ms a frame and,
// with keying on the loop, its SR-2 fell to under one frame a second. The
// frames the worker cannot take are dropped, oldest first, and counted.
namespace {

struct SlowBoxRun {
	uint64_t keyed = 0, noColour = 0;
	uint64_t repeated = 0; // capture slots filled with the previous output
	uint64_t captureSlots = 0; // 20 ms capture slots since the last frame before
	double elapsedS = 0;
	// The script's steps, one every 20 ms: how late the worst came shows
	// whether the loop waited for keying.
	uint64_t worstStepGapUs = 0;
	// A step of the loop before keying was slowed: on a sanitizer build the
	// loop's own turns take longer than the keying.
	double baselineStepS = 0;
};

// kFrames colour frames, one every 20 ms (50 fps), keyed by a box whose
// keying (on the worker) takes keyingUs.
SlowBoxRun runSlowBox(bool freeRunning, unsigned keyingUs, int frames)
{
	Harness h;
	std::atomic<unsigned> delayUs{ 0 };
	DeviceFactory factory = h.factory();
	factory.beforeKeying = [&delayUs] {
		if (unsigned us = delayUs.load())
			usleep(us);
	};
	Daemon daemon("unused.toml", {}, factory);
	SlowBoxRun run;
	if (daemon.start(smallFastSettings()) != 0)
		return run;
	h.colour->setFreeRunning(freeRunning);
	BothCameras cameras(h);
	uint64_t lastStepNs = 0, firstCaptureNs = 0;
	auto deliverBoth = [&] {
		const uint64_t now = monotonicNs();
		if (lastStepNs)
			run.worstStepGapUs = std::max(run.worstStepGapUs, (now - lastStepNs) / 1000);
		lastStepNs = now;
		cameras.deliver();
		run.captureSlots = (cameras.colour.timestampNs - firstCaptureNs + 10'000'000) / 20'000'000;
	};
	Script script(daemon, 20000);
	uint64_t startNs = 0, noColourBefore = 0, publishedBefore = 0, repeatedBefore = 0;
	uint64_t baselineNs = 0;
	script.then([&] {
		baselineNs = monotonicNs();
		cameras.deliver();
	});
	for (int i = 0; i < 10; ++i)
		script.then([&] { cameras.deliver(); });
	script.then([&] { run.baselineStepS = double(monotonicNs() - baselineNs) / 11e9; });
	script.then([&] {
		// Measured from the first frame on: before it, NO SIGNAL is right.
		noColourBefore = h.sink->noColourCount();
		publishedBefore = h.sink->compositeCount();
		repeatedBefore = h.sink->repeatedCount();
		// Slots are counted after the last frame before (two steps
		// without a frame lie between: two slots).
		firstCaptureNs = cameras.colour.timestampNs;
		delayUs = keyingUs;
		startNs = monotonicNs();
	});
	for (int i = 0; i < frames; ++i)
		script.then(deliverBoth);
	// NO SIGNAL counts while the frames come; after the last one it is
	// right once the grace has passed.
	script.then([&] { run.noColour = h.sink->noColourCount() - noColourBefore; });
	// Time for the last frames to come out of the worker.
	for (int i = 0; i < 10; ++i)
		script.then([] {});
	script.run();
	run.elapsedS = double(monotonicNs() - startNs) / 1e9;
	unblockSignals();
	run.repeated = h.sink->repeatedCount() - repeatedBefore;
	run.keyed = (h.sink->compositeCount() - h.sink->noColourCount()) - (publishedBefore - noColourBefore) -
		    run.repeated;
	return run;
}

} // namespace

TEST(DaemonDegraded, ASlowBoxKeysOnItsWorkerAndDropsWhatItCannotKey)
{
	constexpr unsigned kKeyingUs = 40000; // twice the colour period
	constexpr int kFrames = 100;
	const SlowBoxRun run = runSlowBox(true, kKeyingUs, kFrames);
	std::printf("%llu of %d frames keyed in %.2f s; the loop's worst step gap %.1f ms, %.1f ms a step before\n",
		    static_cast<unsigned long long>(run.keyed), kFrames, run.elapsedS, run.worstStepGapUs / 1e3,
		    run.baselineStepS * 1e3);
	EXPECT_GE(run.keyed, uint64_t(kFrames / 4)) << "a slow box must still key what it can";
	EXPECT_EQ(run.noColour, 0u) << "a dropped frame is no lost camera";
	// Issue 29 point 5: every capture slot still gets a frame, the shed
	// ones the previous output again, so the stream keeps its rate. The
	// last frame or two may still be on the worker.
	// (The script's 20 ms steps run late on a loaded machine: their
	// capture times span more slots than frames.)
	std::printf("%llu keyed + %llu repeated of %llu capture slots\n", static_cast<unsigned long long>(run.keyed),
		    static_cast<unsigned long long>(run.repeated), static_cast<unsigned long long>(run.captureSlots));
	EXPECT_GT(run.repeated, 0u);
	EXPECT_GE(run.keyed + run.repeated, run.captureSlots - 2);
	EXPECT_LE(run.keyed + run.repeated, run.captureSlots);
	// Under the sanitizers the loop's own steps are slower than the
	// keying: frames come one a keying, and none need be dropped.
	if (run.baselineStepS * 1e6 > kKeyingUs / 2) {
		std::printf("a step of the loop alone took %.1f ms here: nothing to drop\n", run.baselineStepS * 1e3);
		return;
	}
	// The worker keys one frame per 40 ms at best: about half of them.
	EXPECT_LT(run.keyed, uint64_t(kFrames)) << "no frame was dropped";
	// The loop never waited for a 40 ms keying: its 20 ms steps (the
	// frames and 11 more) took about 2.2 s; waiting would have
	// taken over 4 s. Generous for a loaded machine.
	const double stepsS = (kFrames + 11) * 0.020;
	EXPECT_LT(run.elapsedS, stepsS + 0.5 * kFrames * 0.020) << "the loop waited for keying";
}

// A source that waits for the daemon (a replay not in real time, the soak)
// loses nothing however slow the keying: each frame is keyed.
TEST(DaemonDegraded, ASourceThatWaitsForTheDaemonIsNeverShed)
{
	const SlowBoxRun run = runSlowBox(false, 40000, 60);
	EXPECT_EQ(run.keyed, 60u);
	EXPECT_EQ(run.noColour, 0u);
}
