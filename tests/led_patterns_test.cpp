// The status LED legend (docs/devices.md, "Status LEDs") and the blink patterns.
#include <gtest/gtest.h>

#include "hal/gpio/led_patterns.hpp"

using namespace depthkey;

namespace {

LedPattern patternOf(const StatusSummary &s, StatusLed led)
{
	return ledPatternsFor(s)[static_cast<size_t>(led)];
}

std::string lit(LedPattern p)
{
	std::string s;
	for (unsigned t = 0; t < kLedTicksPerCycle; t++)
		s += ledLit(p, t) ? '#' : '.';
	return s;
}

} // namespace

TEST(LedPatterns, BlinkShapesOverOneSecond)
{
	EXPECT_EQ(kLedTickUs * kLedTicksPerCycle, 1'000'000u);
	EXPECT_EQ(lit(LedPattern::Off), "........");
	EXPECT_EQ(lit(LedPattern::On), "########");
	EXPECT_EQ(lit(LedPattern::SlowBlink), "####....");
	EXPECT_EQ(lit(LedPattern::FastBlink), "#.#.#.#.");
	EXPECT_EQ(lit(LedPattern::Heartbeat), "#.#.....");
	EXPECT_EQ(ledLit(LedPattern::SlowBlink, 8), ledLit(LedPattern::SlowBlink, 0)); // wraps
}

TEST(LedPatterns, AllWellIsHeartbeatCamerasOnRestDark)
{
	StatusSummary s{ .colourOk = true, .depthOk = true, .calibrated = true,
			 .readerAttached = true, .error = false };
	EXPECT_EQ(patternOf(s, StatusLed::Power), LedPattern::Heartbeat);
	EXPECT_EQ(patternOf(s, StatusLed::Depth), LedPattern::On);
	EXPECT_EQ(patternOf(s, StatusLed::Colour), LedPattern::On);
	EXPECT_EQ(patternOf(s, StatusLed::Calibration), LedPattern::Off);
	EXPECT_EQ(patternOf(s, StatusLed::Reader), LedPattern::On);
	EXPECT_EQ(patternOf(s, StatusLed::Error), LedPattern::Off);
	EXPECT_EQ(patternOf(s, StatusLed::Board), LedPattern::On);
}

// The board LED: lost outranks not calibrated (the picture is frozen).
TEST(LedPatterns, BoardLedSaysLostOrNotCalibrated)
{
	StatusSummary s{ .colourOk = true, .depthOk = true, .calibrated = true, .readerAttached = true,
			 .error = false, .boardOk = true, .boardCalibrated = false };
	EXPECT_EQ(patternOf(s, StatusLed::Board), LedPattern::SlowBlink);
	s.boardOk = false;
	EXPECT_EQ(patternOf(s, StatusLed::Board), LedPattern::FastBlink);
	s.boardCalibrated = true;
	EXPECT_EQ(patternOf(s, StatusLed::Board), LedPattern::FastBlink);
	EXPECT_EQ(patternOf(s, StatusLed::Colour), LedPattern::On);
	EXPECT_STREQ(statusLedName(StatusLed::Board), "board");
}

TEST(LedPatterns, EachProblemShowsOnItsOwnLed)
{
	StatusSummary ok{ .colourOk = true, .depthOk = true, .calibrated = true,
			  .readerAttached = true, .error = false };
	StatusSummary s = ok;
	s.depthOk = false;
	EXPECT_EQ(patternOf(s, StatusLed::Depth), LedPattern::FastBlink);
	EXPECT_EQ(patternOf(s, StatusLed::Colour), LedPattern::On);
	s = ok;
	s.colourOk = false;
	EXPECT_EQ(patternOf(s, StatusLed::Colour), LedPattern::FastBlink);
	EXPECT_EQ(patternOf(s, StatusLed::Depth), LedPattern::On);
	s = ok;
	s.calibrated = false;
	EXPECT_EQ(patternOf(s, StatusLed::Calibration), LedPattern::SlowBlink);
	s = ok;
	s.readerAttached = false;
	EXPECT_EQ(patternOf(s, StatusLed::Reader), LedPattern::Off);
	s = ok;
	s.error = true;
	EXPECT_EQ(patternOf(s, StatusLed::Error), LedPattern::On);
	EXPECT_EQ(patternOf(s, StatusLed::Power), LedPattern::Heartbeat);
}

TEST(LedPatterns, NamesForTheJournal)
{
	EXPECT_STREQ(statusLedName(StatusLed::Power), "power");
	EXPECT_STREQ(statusLedName(StatusLed::Calibration), "calibration");
	EXPECT_STREQ(statusLedName(StatusLed::Error), "error");
}
