#include "algo/offset_gate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace depthkey {

double unpairedShare(uint64_t pairedBefore, uint64_t unpairedBefore, uint64_t pairedAfter, uint64_t unpairedAfter)
{
	const uint64_t paired = pairedAfter - pairedBefore, unpaired = unpairedAfter - unpairedBefore;
	return paired + unpaired ? double(unpaired) / double(paired + unpaired) : 0.0;
}

std::string OffsetGate::qualityProblem(const LatencyEstimator::Estimate &e)
{
	char text[96];
	if (e.colourMotionPerS < kMinMotionPerS) {
		std::snprintf(text, sizeof(text), "too little motion (%.2f/s, needs %.2f)", e.colourMotionPerS,
			      kMinMotionPerS);
		return text;
	}
	if (e.depthFrames < kMinDepthFrames) {
		std::snprintf(text, sizeof(text), "%zu depth frames of %zu", e.depthFrames, kMinDepthFrames);
		return text;
	}
	if (e.correlation < kMinCorrelation) {
		std::snprintf(text, sizeof(text), "correlation %.2f below %.2f", e.correlation, kMinCorrelation);
		return text;
	}
	if (e.peakMargin < kMinPeakMargin) {
		std::snprintf(text, sizeof(text), "peak unclear (%.2f above the next, needs %.2f)", e.peakMargin,
			      kMinPeakMargin);
		return text;
	}
	if (std::abs(e.offsetMs) > e.maxLagMs - kEdgeMarginMs) {
		std::snprintf(text, sizeof(text), "at the edge of the +-%d ms search", e.maxLagMs);
		return text;
	}
	return "";
}

bool OffsetGate::update(const LatencyEstimator::Estimate &e, uint64_t paired, uint64_t unpaired)
{
	history_[historyNext_] = { paired, unpaired };
	historyNext_ = (historyNext_ + 1) % history_.size();
	historyCount_ = std::min(historyCount_ + 1, history_.size());

	const double appliedBefore = appliedMs_;
	const bool haveAppliedBefore = haveApplied_;
	if (judging_)
		judge(paired, unpaired);

	if (e.depthFrames == 0 && !e.valid) {
		// Nothing measured yet (or since a reset of the estimator).
		recentCount_ = 0;
		if (!haveApplied_)
			state_ = State::Measuring;
		return haveApplied_ != haveAppliedBefore || appliedMs_ != appliedBefore;
	}
	// An invalid estimate's lag is only where the search began (still room:
	// -300 ms); it is not reported as measured.
	haveMeasured_ = e.valid;
	measuredMs_ = e.valid ? e.offsetMs : 0.0;
	std::string problem = qualityProblem(e);
	if (!problem.empty()) {
		recentCount_ = 0; // stability counts consecutive good estimates
		reason_ = problem;
		state_ = State::Held;
		return haveApplied_ != haveAppliedBefore || appliedMs_ != appliedBefore;
	}
	recent_[recentNext_] = e.offsetMs;
	recentNext_ = (recentNext_ + 1) % kStableCount;
	recentCount_ = std::min(recentCount_ + 1, kStableCount);
	char text[96];
	if (recentCount_ < kStableCount) {
		std::snprintf(text, sizeof(text), "%zu of %zu steady estimates", recentCount_, kStableCount);
		reason_ = text;
		state_ = State::Held;
		return haveApplied_ != haveAppliedBefore || appliedMs_ != appliedBefore;
	}
	std::array<double, kStableCount> sorted = recent_;
	std::sort(sorted.begin(), sorted.end());
	const double spread = sorted.back() - sorted.front();
	if (spread > kStableSpreadMs) {
		std::snprintf(text, sizeof(text), "unsteady (the last %zu spread %.0f ms, needs %.0f)", kStableCount,
			      spread, kStableSpreadMs);
		reason_ = text;
		state_ = State::Held;
		return haveApplied_ != haveAppliedBefore || appliedMs_ != appliedBefore;
	}
	const double median = sorted[kStableCount / 2];
	if (haveRejected_ && std::abs(median - rejectedMs_) <= kStableSpreadMs) {
		std::snprintf(text, sizeof(text), "%+.0f ms was taken back: pairing got worse", rejectedMs_);
		reason_ = text;
		state_ = State::Held;
		return haveApplied_ != haveAppliedBefore || appliedMs_ != appliedBefore;
	}
	reason_.clear();
	state_ = State::Applied;
	if (!haveApplied_ || std::abs(median - appliedMs_) >= kApplyStepMs)
		apply(median, paired, unpaired);
	return haveApplied_ != haveAppliedBefore || appliedMs_ != appliedBefore;
}

void OffsetGate::apply(double offsetMs, uint64_t paired, uint64_t unpaired)
{
	havePrevious_ = haveApplied_;
	previousMs_ = appliedMs_;
	haveApplied_ = true;
	appliedMs_ = offsetMs;
	// The share over the updates before (as many as there are), to compare
	// with the share over the kJudgeUpdates after.
	const size_t back = historyCount_ - 1;
	const Counters &oldest = history_[(historyNext_ + history_.size() - 1 - back) % history_.size()];
	shareBefore_ = unpairedShare(oldest.paired, oldest.unpaired, paired, unpaired);
	atApply_ = { paired, unpaired };
	judging_ = true;
	judgedUpdates_ = 0;
}

void OffsetGate::judge(uint64_t paired, uint64_t unpaired)
{
	if (++judgedUpdates_ < kJudgeUpdates)
		return;
	judging_ = false;
	const double after = unpairedShare(atApply_.paired, atApply_.unpaired, paired, unpaired);
	if (after <= shareBefore_ + kTakeBackRise)
		return;
	haveRejected_ = true;
	rejectedMs_ = appliedMs_;
	haveApplied_ = havePrevious_;
	appliedMs_ = havePrevious_ ? previousMs_ : 0.0;
	havePrevious_ = false;
	recentCount_ = 0;
	char text[128];
	std::snprintf(text, sizeof(text), "%+.0f ms taken back: unpaired %.0f%% after, %.0f%% before", rejectedMs_,
		      after * 100, shareBefore_ * 100);
	reason_ = text;
	state_ = State::Held;
}

std::string OffsetGate::describe() const
{
	char applied[48];
	if (haveApplied_)
		std::snprintf(applied, sizeof(applied), "applied %+.0f ms", appliedMs_);
	else
		std::snprintf(applied, sizeof(applied), "none applied");
	if (state_ == State::Measuring)
		return std::string("measuring, ") + applied;
	char measured[48];
	if (haveMeasured_)
		std::snprintf(measured, sizeof(measured), "measured %+.0f ms", measuredMs_);
	else
		std::snprintf(measured, sizeof(measured), "not measured");
	char text[256];
	if (state_ == State::Applied)
		std::snprintf(text, sizeof(text), "%s, %s", measured, applied);
	else
		std::snprintf(text, sizeof(text), "%s, %s, held: %s", measured, applied, reason_.c_str());
	return text;
}

} // namespace depthkey
