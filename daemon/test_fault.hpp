// TEST-ONLY fault switch, so that the systemd watchdog can be proven to work:
// with DEPTHKEY_TEST_FAULT set in the environment, SIGUSR2 breaks the daemon
// on purpose. Never set it on a box in service.
//   DEPTHKEY_TEST_FAULT=hang   SIGUSR2 blocks the event loop for ever (as a
//                              driver call that never returns would)
//   DEPTHKEY_TEST_FAULT=stall  SIGUSR2 wedges the keying worker at its next
//                              frame and stops publishing (NO SIGNAL too)
//                              while the event loop, status and LEDs go on
// Either way WATCHDOG=1 stops and systemd kills and restarts the daemon.
//   DEPTHKEY_TEST_FAULT=slow   from the start, every frame's keying takes
//                              kSlowKeyingUs longer: a box too slow to key
//                              every frame, which must shed some and still
//                              keep the stream's time (issue 29 point 5)
#pragma once

#include <string_view>

namespace depthkey {

enum class TestFault { None, Hang, Stall, Slow };

// The "slow" fault's extra keying time: 1.5 frame periods at 25 fps.
constexpr unsigned kSlowKeyingUs = 60000;

// Parses the variable's value; false for an unknown one (fault stays None).
bool parseTestFault(std::string_view text, TestFault &fault);

// Reads DEPTHKEY_TEST_FAULT; an unknown value is logged and ignored.
TestFault testFaultFromEnvironment();

// Blocks the calling thread for ever: the "hang" fault.
[[noreturn]] void hangForever();

} // namespace depthkey
