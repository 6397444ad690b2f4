// Whether a measured depth offset (algo/latency_estimator.hpp) deserves to
// be applied to pairing (issue 29 §3). One estimate alone does not: a few
// seconds of lecture can correlate best at a wrong lag, or at the edge of the
// search window, with a high correlation. An estimate is applied only when
//   - it is measured on enough: kMinDepthFrames depth frames and colour
//     motion of at least kMinMotionPerS (a still room has nothing to time);
//   - its peak is clear: at least kMinCorrelation, and kMinPeakMargin above
//     the best other local maximum;
//   - it is not within kEdgeMarginMs of the search window's edge (the true
//     peak may lie outside);
//   - it is stable: the last kStableCount estimates all passed the above and
//     lie within kStableSpreadMs of each other; their median is applied.
// An applied offset that makes pairing worse is taken back: when the share
// of colour frames left unpaired over the kJudgeUpdates updates after it
// rose by more than kTakeBackRise over the kJudgeUpdates before, the
// previous offset returns and the rejected value is not applied again
// (until the measurement moves kStableSpreadMs away from it).
// Pure: fed once a second with the estimate and the pairing counters.
#pragma once

#include "algo/latency_estimator.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>

namespace depthkey {

class OffsetGate
{
public:
	static constexpr size_t kStableCount = 5;
	static constexpr double kStableSpreadMs = 10.0;
	static constexpr double kEdgeMarginMs = LatencyEstimator::kPeakLobeMs; // a whole lobe inside the window
	static constexpr size_t kMinDepthFrames = 80;
	static constexpr double kMinCorrelation = LatencyEstimator::kMinCorrelation;
	static constexpr double kMinPeakMargin = 0.15;
	static constexpr double kMinMotionPerS = 0.1;  // share of the colour grid changing per second
	static constexpr double kApplyStepMs = 3.0;    // smaller moves of the median are not worth a change
	static constexpr size_t kJudgeUpdates = 5;
	static constexpr double kTakeBackRise = 0.05;  // unpaired share, absolute

	enum class State { Measuring, Held, Applied };

	// Once a second. paired/unpaired: the pairer's running counters.
	// Returns true when the offset to apply changed.
	bool update(const LatencyEstimator::Estimate &estimate, uint64_t paired, uint64_t unpaired);
	void reset() { *this = OffsetGate{}; }

	State state() const { return state_; }
	bool haveApplied() const { return haveApplied_; }
	double appliedMs() const { return appliedMs_; }
	double measuredMs() const { return measuredMs_; }
	bool haveMeasured() const { return haveMeasured_; }
	// Why the newest estimate is not applied ("" when it is, or measuring).
	const std::string &reason() const { return reason_; }
	// "measured -41 ms, applied -40 ms", "measured -215 ms, held: ...".
	std::string describe() const;

private:
	// "" when the estimate itself is good enough to count towards stability.
	static std::string qualityProblem(const LatencyEstimator::Estimate &e);
	void apply(double offsetMs, uint64_t paired, uint64_t unpaired);
	void judge(uint64_t paired, uint64_t unpaired);

	std::array<double, kStableCount> recent_{};
	size_t recentCount_ = 0, recentNext_ = 0;
	State state_ = State::Measuring;
	bool haveMeasured_ = false, haveApplied_ = false;
	double measuredMs_ = 0, appliedMs_ = 0;
	std::string reason_;
	// Take-back: the counters when the last offset was applied, and the
	// unpaired share over the updates before it.
	struct Counters {
		uint64_t paired = 0, unpaired = 0;
	};
	std::array<Counters, kJudgeUpdates + 1> history_{}; // the last updates' counters
	size_t historyCount_ = 0, historyNext_ = 0;
	bool judging_ = false;
	size_t judgedUpdates_ = 0;
	Counters atApply_;
	double shareBefore_ = 0;
	bool havePrevious_ = false;
	double previousMs_ = 0;
	bool haveRejected_ = false;
	double rejectedMs_ = 0;
};

// The unpaired share between two counter readings; 0 when no frame came.
double unpairedShare(uint64_t pairedBefore, uint64_t unpairedBefore, uint64_t pairedAfter, uint64_t unpairedAfter);

} // namespace depthkey
