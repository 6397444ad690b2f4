#include "daemon/frame_pairing.hpp"

#include "daemon/log.hpp"
#include "wiring/pipeline_setup.hpp"

#include <cmath>
#include <cstdio>

namespace depthkey {

namespace {

// Depth counts as delivering (DEPTH_OK on NO SIGNAL frames) while its newest
// frame is younger than this; pairing itself uses pairing.max_skew_ms.
constexpr int64_t kDepthStaleNs = 500'000'000;

} // namespace

void FramePairing::configure(const Settings &settings)
{
	settings_ = settings.pairing;
	configurePairingQueue(queue_, settings, offsetNs());
	latency_.configure(settings.segmentation.nearMm, settings.segmentation.farMm);
}

int64_t FramePairing::offsetNs() const
{
	if (!settings_.offsetAuto)
		return int64_t{ settings_.offsetMs } * 1'000'000;
	return gate_.haveApplied() ? int64_t(std::llround(gate_.appliedMs() * 1e6)) : 0;
}

std::string FramePairing::offsetStatus() const
{
	if (settings_.offsetAuto)
		return gate_.describe();
	char text[96];
	if (gate_.haveMeasured())
		std::snprintf(text, sizeof(text), "set %+d ms (measured %+.0f ms, not applied)", settings_.offsetMs,
			      gate_.measuredMs());
	else
		std::snprintf(text, sizeof(text), "set %+d ms", settings_.offsetMs);
	return text;
}

void FramePairing::updateLatency(const std::string &depthName)
{
	estimate_ = latency_.estimate();
	const PairingStats stats = queue_.pairer().stats();
	// A frame keyed with stale depth (beyond max_skew, issue 29 §4) is one a
	// wrong offset left without a pair: it counts as unpaired for the
	// take-back, as the board-only frames of depth truly lost do.
	if (gate_.update(estimate_, stats.paired, stats.unpaired + stats.stale) && settings_.offsetAuto)
		queue_.setOffset(offsetNs());
	{
		// Every estimate (once a second), for working out why a start
		// applied what it did (make offset-trials runs at log_level = "debug").
		char text[320];
		std::snprintf(text, sizeof(text),
			      "offset estimate %+.1f ms: correlation %.2f, margin %.2f, %zu depth frames, motion %.2f/s; %s",
			      estimate_.offsetMs, estimate_.correlation, estimate_.peakMargin, estimate_.depthFrames,
			      estimate_.colourMotionPerS, gate_.describe().c_str());
		logger().debug(text, { { "DEVICE", depthName } });
	}
	// Journaled when what is applied, or why not, changes (not every
	// estimate: they move by a few ms each second).
	std::string line = gate_.state() == OffsetGate::State::Measuring ? std::string() : offsetStatus();
	if (gate_.state() == OffsetGate::State::Applied || !settings_.offsetAuto) {
		// Only the applied value matters while applied or set.
		char text[64];
		std::snprintf(text, sizeof(text), "%d %+.0f", int(gate_.haveApplied()), gate_.appliedMs());
		if (line.empty() || logged_ == text)
			return;
		logged_ = text;
	} else {
		// The kind of reason, without its figures; counting towards
		// stability ("3 of 5 steady estimates") is no news.
		const std::string key = gate_.reason().substr(0, gate_.reason().find_first_of("(0123456789"));
		if (line.empty() || key.empty() || logged_ == key)
			return;
		logged_ = key;
	}
	logger().info("depth offset " + line,
		      { { "DEVICE", depthName },
			{ "DEPTH_OFFSET_MS", std::to_string(std::lround(estimate_.offsetMs)) },
			{ "DEPTH_OFFSET_APPLIED_MS",
			  gate_.haveApplied() ? std::to_string(std::lround(gate_.appliedMs())) : std::string("none") } });
}

bool FramePairing::depthFresh(uint64_t nowNs) const
{
	int64_t ts;
	if (!queue_.pairer().newestNs(ts))
		return false;
	int64_t d = ts - static_cast<int64_t>(nowNs);
	return d <= kDepthStaleNs && d >= -kDepthStaleNs;
}

} // namespace depthkey
