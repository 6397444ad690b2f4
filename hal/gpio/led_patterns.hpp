// The status LED legend as a pure function: which pattern each LED shows for
// a daemon state, and whether a pattern is lit at a given tick. The legend is
// what the technician reads (docs/devices.md, "Status LEDs"); tests pin it down.
//
//   LED          pattern                 meaning
//   power        heartbeat (2 flashes/s) depthkeyd runs and its loop is alive
//                                        (steady on or off: hung or not running)
//   depth        on                      depth camera streaming
//                fast blink (4 Hz)       depth camera missing or failing, retrying
//   colour       on / fast blink         the same for the colour camera
//   calibration  off                     calibration loaded
//                slow blink (1 Hz)       calibration missing: keying is uncalibrated
//   reader       on / off                a recorder is / is not reading the output
//   error        on                      a persistent error is in the journal
//   board        on                      board picture live, composite in board geometry
//                slow blink (1 Hz)       board not calibrated: camera-geometry composite
//                fast blink (4 Hz)       board source lost: its last good picture stays
#pragma once

#include "hal/status_leds.hpp"

#include <array>
#include <cstdint>

namespace depthkey {

enum class StatusLed { Power, Depth, Colour, Calibration, Reader, Error, Board };
constexpr size_t kStatusLedCount = 7;

enum class LedPattern { Off, On, SlowBlink, FastBlink, Heartbeat };

// A pattern is 8 ticks of 125 ms: one second per cycle.
constexpr uint64_t kLedTickUs = 125'000;
constexpr unsigned kLedTicksPerCycle = 8;

using LedPatterns = std::array<LedPattern, kStatusLedCount>;

LedPatterns ledPatternsFor(const StatusSummary &summary);
bool ledLit(LedPattern pattern, unsigned tick);
const char *statusLedName(StatusLed led);

} // namespace depthkey
