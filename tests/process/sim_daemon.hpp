// A depthkeyd on simulated cameras whose shared-memory streams are named
// after the test (prefix.composite, prefix.lecturer), started and ready.
#pragma once

#include "tests/process/daemon_process.hpp"
#include "tests/shm_test_util.hpp" // unlinkStreams

#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <sys/mman.h>

namespace depthkey::test {

// cameras: the config's [colour] / [depth] sections.
inline ::testing::AssertionResult startSimDaemon(DaemonProcess &daemon, const std::string &prefix,
						 const std::string &cameras)
{
	const std::string config = daemon.writeFile(
		"depthkey.toml", cameras + "[output]\ncomposite_name = \"" + prefix + ".composite\"\n"
				 "lecturer_name = \"" + prefix + ".lecturer\"\n");
	if (!daemon.start({ "--config", config }))
		return ::testing::AssertionFailure() << "depthkeyd did not start";
	if (!daemon.waitForNotify("READY=1", std::chrono::seconds(10)))
		return ::testing::AssertionFailure() << "not ready: " << daemon.log();
	return ::testing::AssertionSuccess();
}

} // namespace depthkey::test
