// The TEST-ONLY fault switch (daemon/test_fault.hpp): the values it accepts.
// tests/process/test_fault_daemon_test.cpp arms it in a running daemon.
#include "daemon/test_fault.hpp"

#include <gtest/gtest.h>

using depthkey::TestFault;

TEST(TestFault, ParsesKnownValuesOnly)
{
	TestFault fault = TestFault::Stall;
	EXPECT_TRUE(depthkey::parseTestFault("", fault));
	EXPECT_EQ(fault, TestFault::None);
	EXPECT_TRUE(depthkey::parseTestFault("hang", fault));
	EXPECT_EQ(fault, TestFault::Hang);
	EXPECT_TRUE(depthkey::parseTestFault("stall", fault));
	EXPECT_EQ(fault, TestFault::Stall);
	EXPECT_TRUE(depthkey::parseTestFault("slow", fault));
	EXPECT_EQ(fault, TestFault::Slow);
	fault = TestFault::None;
	EXPECT_FALSE(depthkey::parseTestFault("Hang", fault));
	EXPECT_FALSE(depthkey::parseTestFault("crash", fault));
	EXPECT_EQ(fault, TestFault::None);
}
