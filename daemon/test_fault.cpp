#include "daemon/test_fault.hpp"

#include "daemon/log.hpp"

#include <cstdlib>
#include <string>
#include <unistd.h>

namespace depthkey {

bool parseTestFault(std::string_view text, TestFault &fault)
{
	if (text.empty())
		fault = TestFault::None;
	else if (text == "hang")
		fault = TestFault::Hang;
	else if (text == "stall")
		fault = TestFault::Stall;
	else if (text == "slow")
		fault = TestFault::Slow;
	else
		return false;
	return true;
}

TestFault testFaultFromEnvironment()
{
	const char *value = std::getenv("DEPTHKEY_TEST_FAULT");
	TestFault fault = TestFault::None;
	if (value && !parseTestFault(value, fault))
		logger().warning(std::string("DEPTHKEY_TEST_FAULT=") + value +
				 " ignored: the test faults are \"hang\", \"stall\" and \"slow\"");
	else if (fault != TestFault::None)
		logger().warning(std::string("TEST-ONLY fault switch armed: SIGUSR2 will ") +
				 (fault == TestFault::Hang ? "hang the event loop"
				  : fault == TestFault::Slow ? "(armed already) slow every keying"
							      : "stall the frames"),
				 { { "TEST_FAULT", value } });
	return fault;
}

void hangForever()
{
	for (;;)
		::pause(); // the daemon's signals are blocked: only SIGKILL/SIGABRT end this
}

} // namespace depthkey
