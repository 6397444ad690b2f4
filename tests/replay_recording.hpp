// Small recorded sequences for the replay tests (tests/replay_timeline_test.cpp,
// tests/replay_prefetch_test.cpp): each frame's pixels its own, so a frame
// played can be told from every other.
#pragma once

#include "hal/camera.hpp"
#include "hal/recording/sequence_reader.hpp"
#include "hal/recording/sequence_writer.hpp"

#include <gtest/gtest.h>
#include <string>
#include <vector>

namespace depthkey::test {

constexpr uint64_t kColourPeriodNs = 40'000'000, kDepthPeriodNs = 100'000'000;

// colourFrames of width x height every 40 ms (red = the frame's index) and
// depthFrames of 8x6 every 100 ms (depth = 1000 + its index); a mask per
// colour frame (8-bit grey files to break depth with).
inline void record(const std::string &dir, int colourFrames, int depthFrames, int width = 16, int height = 12)
{
	SequenceWriter writer;
	ASSERT_EQ(writer.open(dir), 0) << writer.describeError();
	for (int i = 0; i < colourFrames; ++i) {
		ColourFrame c;
		c.rgb = RgbImage(width, height, Rgb8{ uint8_t(i), 100, 200 });
		c.timestampNs = 1'000'000'000 + i * kColourPeriodNs;
		c.sequence = i + 1;
		ASSERT_EQ(writer.writeColour(c), 0) << writer.describeError();
		ASSERT_EQ(writer.writeMask(Gray8Image(width, height, 255), c.timestampNs, c.sequence), 0);
	}
	for (int i = 0; i < depthFrames; ++i) {
		DepthFrame d;
		d.depthMm = Gray16Image(8, 6, uint16_t(1000 + i));
		d.amplitude = Gray16Image(8, 6, 5000);
		d.intensity = Gray16Image(8, 6, 5000);
		d.timestampNs = 1'000'000'000 + i * kDepthPeriodNs;
		d.sequence = i + 1;
		ASSERT_EQ(writer.writeDepth(d), 0) << writer.describeError();
	}
}

inline std::vector<SequenceEntry> listed(const std::string &dir, bool colour)
{
	SequenceReader reader;
	EXPECT_EQ(reader.open(dir), 0) << reader.describeError();
	return colour ? reader.colour() : reader.depth();
}

// Reports of a camera's status that say Lost.
inline int lostReports(const std::vector<DeviceStatus> &reports)
{
	int n = 0;
	for (const DeviceStatus &s : reports)
		n += s.state == DeviceState::Lost;
	return n;
}

} // namespace depthkey::test
