// Issue 29 §3 at the algo level: many starts of the depth-offset estimator
// (algo/latency_estimator.hpp) and its trust gate (algo/offset_gate.hpp) on
// the simulated lecture, as `make offset-trials` starts the daemon: each
// start sees 30 s of the lecture from its own starting point, at colour
// rates of 25, 30 and 15 fps, some with colour frames missed as on a busy
// box, timestamps jittered as the simulator jitters them; the gate is fed
// once a second with pairing that never fails. The applied offset must be
// within 10 ms of the truth in all but one start and never more than 30 ms
// away (nor missing), and at the end of each start the gate applies (the
// estimate has converged, not "unsteady"); a still scene applies nothing; an
// offset that changes is found again.
#include <gtest/gtest.h>

#include "algo/latency_estimator.hpp"
#include "algo/offset_gate.hpp"
#include "hal/sim/lecture_simulator.hpp"
#include "hal/sim/sim_sequence.hpp"

#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

using namespace depthkey;

namespace {

constexpr int kWidth = 320, kHeight = 240, kDepthFps = 10;
constexpr uint64_t kSecondNs = 1'000'000'000;

// One start: an estimator and a gate that see the stream from startNs on.
struct Start {
	uint64_t startNs = 0;
	LatencyEstimator estimator;
	OffsetGate gate;
	uint64_t nextUpdateNs = 0, paired = 0;

	explicit Start(uint64_t start) : startNs(start), nextUpdateNs(start + kSecondNs)
	{
		SegmentationSettings segmentation;
		estimator.configure(segmentation.nearMm, segmentation.farMm);
	}
	void update(uint64_t nowNs)
	{
		while (nowNs >= nextUpdateNs) {
			paired += 25;
			gate.update(estimator.estimate(), paired, 0);
			nextUpdateNs += kSecondNs;
		}
	}
};

// A run of the simulated lecture feeding every start in its window
// [startNs, startNs + seconds). Colour frames are missed pseudo-randomly at
// missedShare (a busy box's uneven rate). latencyAt(t) sets the truth.
struct Lecture {
	uint64_t seed = 1;
	int colourFps = 25;
	double missedShare = 0;
	double latencyMs = 40;
	// A second latency from changeAtS on (0: none).
	double changeAtS = 0, latencyAfterMs = 0;
};

void feed(const Lecture &run, std::vector<std::unique_ptr<Start>> &starts, int seconds)
{
	uint64_t endNs = 0;
	for (const auto &s : starts)
		endNs = std::max(endNs, s->startNs + uint64_t(seconds) * kSecondNs);
	auto renderPart = [&](double latencyMs, uint64_t fromNs, uint64_t toNs) {
		SimSettings sim;
		sim.seed = run.seed;
		sim.depthLatencyMs = latencyMs;
		SimSequence sequence;
		sequence.configure(sim, kWidth, kHeight, run.colourFps, kDepthFps);
		ColourFrame colour;
		GroundTruth truth;
		uint32_t random = uint32_t(run.seed) * 2654435761u + uint32_t(run.colourFps);
		for (uint64_t n = 0;; ++n) {
			const uint64_t nominalNs = n * kSecondNs / uint64_t(run.colourFps);
			if (nominalNs >= toNs)
				break;
			if (nominalNs + kSecondNs < fromNs)
				continue; // the other latency's part
			sequence.frame(n, colour, truth, [&](const DepthFrame &d) {
				if (d.timestampNs < fromNs)
					return;
				for (auto &s : starts)
					if (d.timestampNs >= s->startNs && d.timestampNs < s->startNs + uint64_t(seconds) * kSecondNs)
						s->estimator.addDepth(d, d.timestampNs);
			});
			random = random * 1664525u + 1013904223u;
			if (colour.timestampNs < fromNs || double(random >> 8) < run.missedShare * double(1u << 24))
				continue;
			for (auto &s : starts) {
				if (colour.timestampNs < s->startNs || colour.timestampNs >= s->startNs + uint64_t(seconds) * kSecondNs)
					continue;
				s->estimator.addColour(colour.rgb, colour.timestampNs);
				s->update(colour.timestampNs);
			}
		}
	};
	if (run.changeAtS > 0) {
		const uint64_t changeNs = uint64_t(run.changeAtS * 1e9);
		renderPart(run.latencyMs, 0, changeNs);
		renderPart(run.latencyAfterMs, changeNs, endNs);
	} else {
		renderPart(run.latencyMs, 0, endNs);
	}
}

} // namespace

// 20 starts: 4 seeds x 5 starting points, at 25, 30 and 15 fps, half of
// them with a third of the colour frames missed.
TEST(OffsetStarts, TwentyStartsApplyWithin10MsOfTheTruth)
{
	constexpr int kSeconds = 30;
	const Lecture runs[] = {
		{ 1, 25, 0.0 },
		{ 2, 30, 0.33 },
		{ 3, 15, 0.0 },
		{ 4, 25, 0.33 },
	};
	int within10 = 0, total = 0;
	double worst = 0;
	for (const Lecture &run : runs) {
		std::vector<std::unique_ptr<Start>> starts;
		for (int k = 0; k < 5; ++k)
			starts.push_back(std::make_unique<Start>(uint64_t(k) * 7 * kSecondNs));
		feed(run, starts, kSeconds);
		for (const auto &s : starts) {
			++total;
			const double error = s->gate.haveApplied() ? std::abs(s->gate.appliedMs() + run.latencyMs) : 1e9;
			std::printf("seed %llu, %d fps, %.0f%% missed, start %2llu s: %s (error %.1f ms)\n",
				    static_cast<unsigned long long>(run.seed), run.colourFps, run.missedShare * 100,
				    static_cast<unsigned long long>(s->startNs / kSecondNs), s->gate.describe().c_str(),
				    error);
			within10 += error <= 10.0;
			worst = std::max(worst, error);
			EXPECT_LE(error, 30.0) << "seed " << run.seed << " start " << s->startNs / kSecondNs;
			// Converged: at the end the estimates agree and the gate
			// applies them (a sliding window's wander leaves it held,
			// "unsteady", on an early value).
			EXPECT_EQ(s->gate.state(), OffsetGate::State::Applied)
				<< "seed " << run.seed << " start " << s->startNs / kSecondNs << ": " << s->gate.describe();
		}
	}
	std::printf("%d of %d starts within 10 ms, the worst %.1f ms off\n", within10, total, worst);
	EXPECT_GE(within10, total - 1);
}

// The daemon's event loop on a busy box (the simulated cameras are its
// timers, hal/sim/sim_cameras.hpp): keying stalls it now and then, and the
// colour and depth ticks that fell in a stall fire together at its end, each
// frame stamped when it fires and showing the scene of that moment (depth:
// 40 ms before). Live, the colour then has a gap just before many depth
// frames and a frame right at them; reading the colour motion off such gaps
// pulled the estimate 15-30 ms towards 0 (make offset-trials: -13, -23, -26
// ms applied). 5 starts of 30 s at 25 fps, a stall of 120-250 ms every
// 0.3-0.8 s.
TEST(OffsetStarts, LoopStallsDoNotPullTheOffsetTowardsZero)
{
	constexpr int kSeconds = 30, kStarts = 5;
	constexpr double kLatencyS = 0.040;
	SimSettings settings;
	settings.seed = 5;
	LectureSimulator sim;
	sim.configure(settings, kWidth, kHeight);
	std::vector<std::unique_ptr<Start>> starts;
	for (int k = 0; k < kStarts; ++k)
		starts.push_back(std::make_unique<Start>(uint64_t(k) * 7 * kSecondNs));
	const double endS = (kStarts - 1) * 7.0 + kSeconds;
	ColourFrame colour;
	DepthFrame depth;
	uint32_t random = 12345;
	auto uniform = [&random] {
		random = random * 1664525u + 1013904223u;
		return double(random >> 8) / double(1u << 24);
	};
	double nextColour = 0.04, nextDepth = 0.013, stallAt = 0.5, stallEnd = 0;
	auto within = [&](const Start &s, uint64_t ns) {
		return ns >= s.startNs && ns < s.startNs + uint64_t(kSeconds) * kSecondNs;
	};
	while (nextColour < endS) {
		// The next tick, or the end of the stall it falls in.
		const bool colourFirst = nextColour <= nextDepth;
		double fire = colourFirst ? nextColour : nextDepth;
		if (fire >= stallAt) {
			stallEnd = stallAt + 0.12 + 0.13 * uniform();
			stallAt = stallEnd + 0.3 + 0.5 * uniform();
		}
		if (fire < stallEnd)
			fire = stallEnd;
		const uint64_t ns = uint64_t(fire * 1e9);
		if (colourFirst) {
			sim.renderColour(fire, colour, nullptr);
			for (auto &s : starts)
				if (within(*s, ns)) {
					s->estimator.addColour(colour.rgb, ns);
					s->update(ns);
				}
			// A periodic timer: the ticks missed in a stall are one.
			while (nextColour <= fire)
				nextColour += 0.04;
		} else {
			sim.renderDepth(fire - kLatencyS, depth);
			for (auto &s : starts)
				if (within(*s, ns))
					s->estimator.addDepth(depth, ns);
			while (nextDepth <= fire)
				nextDepth += 0.1;
		}
	}
	for (const auto &s : starts) {
		const double error = s->gate.haveApplied() ? std::abs(s->gate.appliedMs() + kLatencyS * 1e3) : 1e9;
		std::printf("stalls, start %2llu s: %s (error %.1f ms)\n",
			    static_cast<unsigned long long>(s->startNs / kSecondNs), s->gate.describe().c_str(), error);
		EXPECT_LE(error, 10.0) << "start " << s->startNs / kSecondNs;
	}
}

// A still room: the same colour and depth picture every frame, 30 s at
// jittered times: nothing to time, nothing applied.
TEST(OffsetStarts, StillSceneAppliesNothing)
{
	Start s(0);
	RgbImage still(kWidth, kHeight, Rgb8{ 30, 60, 40 });
	DepthFrame depth;
	depth.depthMm = Gray16Image(kWidth / 2, kHeight / 2, 1200); // in range: the lecturer standing still
	for (uint64_t n = 0; n < 30 * 25; ++n) {
		const uint64_t t = n * 40'000'000 + (n * 7919 % 5) * 1'000'000;
		if (n % 5 == 0)
			s.estimator.addDepth(depth, t + 40'000'000);
		s.estimator.addColour(still, t);
		s.update(t);
	}
	EXPECT_FALSE(s.gate.haveApplied()) << s.gate.describe();
	EXPECT_NE(s.gate.describe().find("too little motion"), std::string::npos) << s.gate.describe();
}

// The depth camera's latency changes from 40 to 90 ms (a firmware update, a
// USB hub): the estimate follows, and the gate applies the new value.
TEST(OffsetStarts, AChangedOffsetIsFoundAgain)
{
	constexpr int kSeconds = 240;
	Lecture run{ 1, 25, 0.0, 40.0, 60.0, 90.0 };
	std::vector<std::unique_ptr<Start>> starts;
	starts.push_back(std::make_unique<Start>(0));
	feed(run, starts, kSeconds);
	const OffsetGate &gate = starts[0]->gate;
	std::printf("after 60 s at 40 ms and %d s at 90 ms: %s\n", kSeconds - 60, gate.describe().c_str());
	ASSERT_TRUE(gate.haveApplied());
	EXPECT_NEAR(gate.appliedMs(), -90.0, 10.0);
}
