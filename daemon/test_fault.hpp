// TEST-ONLY fault switch, so that the systemd watchdog can be proven to work:
// with DEPTHKEY_TEST_FAULT set in the environment, SIGUSR2 breaks the daemon
// on purpose. Never set it on a box in service.
//   DEPTHKEY_TEST_FAULT=hang   SIGUSR2 blocks the event loop for ever (as a
//                              driver call that never returns would)
//   DEPTHKEY_TEST_FAULT=stall  SIGUSR2 wedges the keying worker at its next
//                              frame and stops publishing (NO SIGNAL too)
//                              while the event loop, status and LEDs go on
// Either way WATCHDOG=1 stops and systemd kills and restarts the daemon.
#pragma once

#include <string_view>

namespace depthkey {

enum class TestFault { None, Hang, Stall };

// Parses the variable's value; false for an unknown one (fault stays None).
bool parseTestFault(std::string_view text, TestFault &fault);

// Reads DEPTHKEY_TEST_FAULT; an unknown value is logged and ignored.
TestFault testFaultFromEnvironment();

// Blocks the calling thread for ever: the "hang" fault.
[[noreturn]] void hangForever();

} // namespace depthkey
