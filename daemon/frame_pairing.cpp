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
	return estimate_.valid ? int64_t(std::llround(estimate_.offsetMs * 1e6)) : 0;
}

void FramePairing::updateLatency(const std::string &depthName)
{
	estimate_ = latency_.estimate();
	if (!estimate_.valid)
		return;
	if (settings_.offsetAuto)
		queue_.setOffset(offsetNs());
	if (std::abs(estimate_.offsetMs - loggedMs_) >= 5.0) {
		loggedMs_ = estimate_.offsetMs;
		char text[160];
		std::snprintf(text, sizeof(text), "depth offset measured: %+.0f ms (correlation %.2f)%s",
			      estimate_.offsetMs, estimate_.correlation,
			      settings_.offsetAuto ? ", applied" : "; pairing.offset_ms is set, not applied");
		logger().info(text, { { "DEVICE", depthName },
				      { "DEPTH_OFFSET_MS", std::to_string(std::lround(estimate_.offsetMs)) } });
	}
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
