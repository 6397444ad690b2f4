#include "hal/sr2/sr2_frame_parser.hpp"

#include "hal/sr2/sr2_protocol.hpp"

#include <algorithm>

namespace depthkey {

namespace {

uint16_t wordAt(const uint8_t *image, size_t i)
{
	return static_cast<uint16_t>(image[2 * i] | image[2 * i + 1] << 8);
}

Sr2FrameCheck checkDistance(const uint8_t *distance)
{
	size_t saturated = 0;
	bool flat = true;
	uint16_t first = wordAt(distance, 0);
	for (size_t i = 0; i < sr2::kPixels; i++) {
		uint16_t w = wordAt(distance, i);
		saturated += w == 0xFFFF;
		flat = flat && w == first;
	}
	if (flat)
		return Sr2FrameCheck::Flat;
	if (saturated > sr2::kMaxSaturatedPixels)
		return Sr2FrameCheck::Saturated;
	return Sr2FrameCheck::Ok;
}

} // namespace

const char *sr2FrameCheckName(Sr2FrameCheck check)
{
	switch (check) {
	case Sr2FrameCheck::Ok:
		return "ok";
	case Sr2FrameCheck::Short:
		return "short";
	case Sr2FrameCheck::TooLong:
		return "too long";
	case Sr2FrameCheck::Saturated:
		return "saturated";
	case Sr2FrameCheck::Flat:
		return "flat";
	}
	return "unknown";
}

Sr2FrameCheck parseSr2Frame(const uint8_t *data, size_t length, int minMm, int maxMm,
			    DepthFrame &out, Sr2FrameStats &stats)
{
	if (length < sr2::kFrameBytes)
		return Sr2FrameCheck::Short;
	if (length > sr2::kReadBytes)
		return Sr2FrameCheck::TooLong;
	const uint8_t *distance = data + sr2::kDistanceImage * sr2::kImageBytes;
	const uint8_t *intensity = data + sr2::kIntensityImage * sr2::kImageBytes;
	const uint8_t *amplitude = data + sr2::kAmplitudeImage * sr2::kImageBytes;
	Sr2FrameCheck check = checkDistance(distance);
	if (check != Sr2FrameCheck::Ok)
		return check;

	out.depthMm.resize(sr2::kWidth, sr2::kHeight);
	out.intensity.resize(sr2::kWidth, sr2::kHeight);
	out.amplitude.resize(sr2::kWidth, sr2::kHeight);
	uint16_t *mm = out.depthMm.data();
	uint16_t *in = out.intensity.data();
	uint16_t *am = out.amplitude.data();
	uint64_t intensitySum = 0;
	constexpr uint32_t kHalf = 1u << (sr2::kDistanceShift - 1);
	for (size_t i = 0; i < sr2::kPixels; i++) {
		// raw * 7500 < 2^29: fits 32 bits; + half rounds to nearest mm.
		uint32_t d = (wordAt(distance, i) * sr2::kRangeMm + kHalf) >> sr2::kDistanceShift;
		bool inRange = static_cast<int>(d) >= minMm && static_cast<int>(d) <= maxMm;
		mm[i] = inRange ? static_cast<uint16_t>(d) : 0;
		in[i] = wordAt(intensity, i);
		am[i] = wordAt(amplitude, i);
		intensitySum += in[i];
	}
	stats.meanIntensity = static_cast<uint32_t>(intensitySum / sr2::kPixels);
	return Sr2FrameCheck::Ok;
}

int sr2NextIntegrationTime(int current, uint32_t meanIntensity, int low, int high)
{
	int mean = static_cast<int>(meanIntensity);
	if (mean >= low && mean <= high)
		return current;
	int target = (low + high) / 2;
	int step = (target - mean) / sr2::kAutoIntegrationGainDivisor;
	if (step == 0)
		step = target > mean ? 1 : -1; // always move when outside the window
	return std::clamp(current + step, 0, 255);
}

} // namespace depthkey
