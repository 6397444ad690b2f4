#include "tools/sr2_emulator/sr2_frame_encoder.hpp"

#include "hal/sr2/sr2_protocol.hpp"

#include <algorithm>

namespace depthkey {

namespace {

void putWord(uint8_t *image, size_t i, uint16_t word)
{
	image[2 * i] = static_cast<uint8_t>(word);
	image[2 * i + 1] = static_cast<uint8_t>(word >> 8);
}

// The inverse of the backend's mm = raw * 7500 / 65536, rounded; 0xFFFF is
// the camera's saturation word and never a distance.
uint16_t rawDistance(uint16_t mm)
{
	uint32_t raw = (static_cast<uint32_t>(mm) << sr2::kDistanceShift) + sr2::kRangeMm / 2;
	return static_cast<uint16_t>(std::min<uint32_t>(raw / sr2::kRangeMm, 0xFFFE));
}

uint64_t mix(uint64_t x)
{
	x ^= x >> 33;
	x *= 0xff51afd7ed558ccdULL;
	x ^= x >> 33;
	return x;
}

} // namespace

const char *sr2FrameFaultName(Sr2FrameFault fault)
{
	switch (fault) {
	case Sr2FrameFault::None:
		return "none";
	case Sr2FrameFault::Short:
		return "short";
	case Sr2FrameFault::Corrupt:
		return "corrupt";
	case Sr2FrameFault::Flat:
		return "flat";
	}
	return "unknown";
}

size_t encodeSr2Frame(const DepthFrame &frame, Sr2FrameFault fault, uint64_t seed,
		      std::vector<uint8_t> &raw)
{
	raw.resize(sr2::kFrameBytes);
	uint8_t *distance = raw.data() + sr2::kDistanceImage * sr2::kImageBytes;
	uint8_t *intensity = raw.data() + sr2::kIntensityImage * sr2::kImageBytes;
	uint8_t *amplitude = raw.data() + sr2::kAmplitudeImage * sr2::kImageBytes;
	for (size_t i = 0; i < sr2::kPixels; i++) {
		uint16_t d = rawDistance(frame.depthMm.data()[i]);
		if (fault == Sr2FrameFault::Corrupt)
			d = mix(seed + i) & 1 ? 0xFFFF : static_cast<uint16_t>(mix(seed ^ i));
		else if (fault == Sr2FrameFault::Flat)
			d = 0x5a5a;
		putWord(distance, i, d);
		putWord(intensity, i, frame.intensity.data()[i]);
		putWord(amplitude, i, frame.amplitude.data()[i]);
	}
	// Half a frame, and not a multiple of the packet size, so the short
	// packet ends the host's read early as a cut transfer would.
	return fault == Sr2FrameFault::Short ? sr2::kFrameBytes / 2 + 100 : sr2::kFrameBytes;
}

} // namespace depthkey
