// The preview page's last errors (daemon/recent_errors.hpp): distinct lines,
// newest first, a repeat moved to the front with its count, at most kKept.
#include "daemon/recent_errors.hpp"

#include <gtest/gtest.h>

using namespace depthkey;

TEST(RecentErrors, KeepsTheLastDistinctLinesNewestFirst)
{
	RecentErrors errors;
	errors.add("colour camera lost", 100);
	errors.add("depth camera lost", 200);
	errors.add("colour camera lost", 300);
	auto list = errors.list();
	ASSERT_EQ(list.size(), 2u);
	EXPECT_EQ(list[0].message, "colour camera lost");
	EXPECT_EQ(list[0].realtimeNs, 300u);
	EXPECT_EQ(list[0].count, 2u);
	EXPECT_EQ(list[1].message, "depth camera lost");
	EXPECT_EQ(list[1].count, 1u);

	for (int i = 0; i < 20; i++)
		errors.add("error " + std::to_string(i), 1000 + i);
	list = errors.list();
	ASSERT_EQ(list.size(), RecentErrors::kKept);
	EXPECT_EQ(list.front().message, "error 19");
	EXPECT_EQ(list.back().message, "error " + std::to_string(20 - RecentErrors::kKept));
}
