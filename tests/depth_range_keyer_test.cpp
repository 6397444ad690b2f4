#include "algo/depth_range_keyer.hpp"

#include <gtest/gtest.h>

using namespace depthkey;

TEST(DepthRangeKeyer, KeysPixelsInsideTheIntervalAtColourResolution)
{
	Gray16Image depth(4, 2, 2000);
	depth.at(1, 0) = 1200; // lecturer
	depth.at(2, 1) = 0;    // no measurement
	depth.at(3, 1) = 500;  // exactly near: inside
	DepthRangeKeyer keyer;
	keyer.configure(8, 4, 4, 2);
	Gray8Image alpha;
	keyer.key(depth, 500, 1600, alpha);
	ASSERT_EQ(alpha.width(), 8);
	ASSERT_EQ(alpha.height(), 4);
	for (int y = 0; y < 4; ++y)
		for (int x = 0; x < 8; ++x) {
			uint16_t d = depth.at(x / 2, y / 2);
			bool inside = d >= 500 && d <= 1600;
			EXPECT_EQ(alpha.at(x, y), inside ? 255 : 0) << x << "," << y;
		}
}

TEST(DepthRangeKeyer, FrameOfUnexpectedSizeKeysNothing)
{
	DepthRangeKeyer keyer;
	keyer.configure(8, 4, 4, 2);
	Gray16Image wrong(3, 3, 1000);
	Gray8Image alpha;
	keyer.key(wrong, 500, 1600, alpha);
	for (size_t i = 0; i < alpha.size(); ++i)
		EXPECT_EQ(alpha.data()[i], 0);
}
