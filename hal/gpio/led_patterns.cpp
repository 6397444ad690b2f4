#include "hal/gpio/led_patterns.hpp"

namespace depthkey {

namespace {

// Bit n set = lit during tick n of the one-second cycle.
uint8_t patternBits(LedPattern pattern)
{
	switch (pattern) {
	case LedPattern::Off:
		return 0x00;
	case LedPattern::On:
		return 0xFF;
	case LedPattern::SlowBlink:
		return 0x0F; // 500 ms on, 500 ms off
	case LedPattern::FastBlink:
		return 0x55; // 125 ms on, 125 ms off: 4 Hz
	case LedPattern::Heartbeat:
		return 0x05; // two short flashes, then dark
	}
	return 0;
}

LedPattern cameraPattern(bool ok)
{
	return ok ? LedPattern::On : LedPattern::FastBlink;
}

} // namespace

LedPatterns ledPatternsFor(const StatusSummary &s)
{
	LedPatterns p{};
	p[static_cast<size_t>(StatusLed::Power)] = LedPattern::Heartbeat;
	p[static_cast<size_t>(StatusLed::Depth)] = cameraPattern(s.depthOk);
	p[static_cast<size_t>(StatusLed::Colour)] = cameraPattern(s.colourOk);
	p[static_cast<size_t>(StatusLed::Calibration)] =
		s.calibrated ? LedPattern::Off : LedPattern::SlowBlink;
	p[static_cast<size_t>(StatusLed::Reader)] = s.readerAttached ? LedPattern::On : LedPattern::Off;
	p[static_cast<size_t>(StatusLed::Error)] = s.error ? LedPattern::On : LedPattern::Off;
	p[static_cast<size_t>(StatusLed::Board)] = !s.boardOk		? LedPattern::FastBlink
						   : !s.boardCalibrated ? LedPattern::SlowBlink
									: LedPattern::On;
	return p;
}

bool ledLit(LedPattern pattern, unsigned tick)
{
	return (patternBits(pattern) >> (tick % kLedTicksPerCycle)) & 1;
}

const char *statusLedName(StatusLed led)
{
	switch (led) {
	case StatusLed::Power:
		return "power";
	case StatusLed::Depth:
		return "depth";
	case StatusLed::Colour:
		return "colour";
	case StatusLed::Calibration:
		return "calibration";
	case StatusLed::Reader:
		return "reader";
	case StatusLed::Error:
		return "error";
	case StatusLed::Board:
		return "board";
	}
	return "unknown";
}

} // namespace depthkey
