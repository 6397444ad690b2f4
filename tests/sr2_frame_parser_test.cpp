// SR-2 frames: the register/scale table, good frames converted exactly, and
// every kind of bad frame refused without touching the last good frame.
#include <gtest/gtest.h>

#include "hal/sr2/sr2_frame_parser.hpp"
#include "hal/sr2/sr2_protocol.hpp"

#include <vector>

using namespace depthkey;

namespace {

// A plausible frame: distance ramps with x, intensity and amplitude too.
std::vector<uint8_t> makeFrame(size_t length = sr2::kReadBytes)
{
	std::vector<uint8_t> raw(length, 0);
	for (size_t i = 0; i < sr2::kPixels; i++) {
		uint16_t words[3] = { static_cast<uint16_t>(8000 + (i % sr2::kWidth) * 100),
				      static_cast<uint16_t>(15000 + i % 7),
				      static_cast<uint16_t>(2000 + i % 5) };
		for (int img = 0; img < 3; img++) {
			size_t at = img * sr2::kImageBytes + 2 * i;
			if (at + 1 < raw.size()) {
				raw[at] = words[img] & 0xff;
				raw[at + 1] = words[img] >> 8;
			}
		}
	}
	return raw;
}

void setDistance(std::vector<uint8_t> &raw, size_t i, uint16_t w)
{
	raw[2 * i] = w & 0xff;
	raw[2 * i + 1] = w >> 8;
}

} // namespace

TEST(Sr2Protocol, TableMatchesTheKnownFacts)
{
	EXPECT_EQ(sr2::kVendorId, 0x0852);
	EXPECT_EQ(sr2::kProductId, 0x0071);
	EXPECT_EQ(sr2::kRegOutputMode.address, 0x02);
	EXPECT_EQ(sr2::kOutputDistanceIntensityAmplitude, 0xC0);
	EXPECT_EQ(sr2::kRegIntegrationTime.address, 0x09);
	EXPECT_EQ(sr2::kEndpointFramesIn, 0x88);
	EXPECT_EQ(sr2::kEndpointRegistersOut, 0x02);
	EXPECT_EQ(sr2::kRequestTypeVendorOut, 0x40);
	EXPECT_EQ(sr2::kRequestFrame, 0xB0);
	EXPECT_EQ(sr2::kFrameBytes, 160u * 124u * 2u * 3u);
	EXPECT_EQ(sr2::kReadBytes % 512, 0u);
	EXPECT_GE(sr2::kReadBytes, sr2::kFrameBytes);
	EXPECT_LT(sr2::kReadBytes - sr2::kFrameBytes, 512u);
}

TEST(Sr2FrameParser, GoodFrameConvertsDistanceIntensityAmplitude)
{
	std::vector<uint8_t> raw = makeFrame();
	setDistance(raw, 1, 0xFFFF);           // one saturated word is tolerated
	DepthFrame frame;
	Sr2FrameStats stats;
	ASSERT_EQ(parseSr2Frame(raw.data(), raw.size(), 0, 7500, frame, stats), Sr2FrameCheck::Ok);
	ASSERT_EQ(frame.depthMm.width(), 160);
	ASSERT_EQ(frame.depthMm.height(), 124);
	for (int x : { 0, 5, 159 }) {
		double raw16 = 8000 + x * 100;
		EXPECT_NEAR(frame.depthMm.at(x, 3), raw16 * 7500.0 / 65536.0, 0.5) << x;
	}
	EXPECT_EQ(frame.depthMm.at(1, 0), 7500);   // 0xFFFF -> 7499.9 mm
	EXPECT_EQ(frame.intensity.at(0, 0), 15000);
	EXPECT_EQ(frame.amplitude.at(3, 0), 2003);
	EXPECT_NEAR(stats.meanIntensity, 15003, 1);
}

TEST(Sr2FrameParser, ExactLengthWithoutPaddingIsAccepted)
{
	std::vector<uint8_t> raw = makeFrame(sr2::kFrameBytes);
	DepthFrame frame;
	Sr2FrameStats stats;
	EXPECT_EQ(parseSr2Frame(raw.data(), raw.size(), 0, 7500, frame, stats), Sr2FrameCheck::Ok);
}

TEST(Sr2FrameParser, OutOfRangeDistancesBecomeNoMeasurement)
{
	std::vector<uint8_t> raw = makeFrame();
	DepthFrame frame;
	Sr2FrameStats stats;
	ASSERT_EQ(parseSr2Frame(raw.data(), raw.size(), 1000, 1400, frame, stats), Sr2FrameCheck::Ok);
	// x = 0: 915 mm (below), x = 20: 1144 mm (inside), x = 50: 1488 mm (above)
	EXPECT_EQ(frame.depthMm.at(0, 0), 0);
	EXPECT_EQ(frame.depthMm.at(20, 0), 1144);
	EXPECT_EQ(frame.depthMm.at(50, 0), 0);
}

TEST(Sr2FrameParser, BadFramesAreRefusedAndLeaveTheLastGoodFrame)
{
	DepthFrame frame;
	Sr2FrameStats stats;
	std::vector<uint8_t> good = makeFrame();
	ASSERT_EQ(parseSr2Frame(good.data(), good.size(), 0, 7500, frame, stats), Sr2FrameCheck::Ok);
	const DepthFrame before = frame;

	std::vector<uint8_t> shortFrame = makeFrame(sr2::kFrameBytes - 1);
	EXPECT_EQ(parseSr2Frame(shortFrame.data(), shortFrame.size(), 0, 7500, frame, stats),
		  Sr2FrameCheck::Short);
	EXPECT_EQ(parseSr2Frame(good.data(), 0, 0, 7500, frame, stats), Sr2FrameCheck::Short);

	std::vector<uint8_t> longFrame = makeFrame(sr2::kReadBytes + 512);
	EXPECT_EQ(parseSr2Frame(longFrame.data(), longFrame.size(), 0, 7500, frame, stats),
		  Sr2FrameCheck::TooLong);

	std::vector<uint8_t> flat(sr2::kReadBytes, 0x00);
	EXPECT_EQ(parseSr2Frame(flat.data(), flat.size(), 0, 7500, frame, stats), Sr2FrameCheck::Flat);
	std::vector<uint8_t> filler(sr2::kReadBytes, 0xAB);
	EXPECT_EQ(parseSr2Frame(filler.data(), filler.size(), 0, 7500, frame, stats),
		  Sr2FrameCheck::Flat);

	std::vector<uint8_t> saturated = makeFrame();
	for (size_t i = 0; i <= sr2::kMaxSaturatedPixels; i++)
		setDistance(saturated, i, 0xFFFF); // one more than allowed
	EXPECT_EQ(parseSr2Frame(saturated.data(), saturated.size(), 0, 7500, frame, stats),
		  Sr2FrameCheck::Saturated);

	EXPECT_EQ(frame.depthMm, before.depthMm);
	EXPECT_EQ(frame.intensity, before.intensity);
	EXPECT_EQ(frame.amplitude, before.amplitude);
}

TEST(Sr2AutoIntegration, MovesTowardsTheWindowAndStaysInside)
{
	EXPECT_EQ(sr2NextIntegrationTime(40, 16000, 14000, 18000), 40);     // inside
	EXPECT_EQ(sr2NextIntegrationTime(40, 6000, 14000, 18000), 50);      // (16000-6000)/1000
	EXPECT_EQ(sr2NextIntegrationTime(40, 26000, 14000, 18000), 30);
	EXPECT_EQ(sr2NextIntegrationTime(40, 13900, 14000, 18000), 42);     // 2100/1000 = 2
	EXPECT_EQ(sr2NextIntegrationTime(40, 18100, 14000, 18000), 38);
	EXPECT_EQ(sr2NextIntegrationTime(40, 15999, 16000, 16001), 41);     // at least one step
	EXPECT_EQ(sr2NextIntegrationTime(250, 0, 14000, 18000), 255);       // clamped
	EXPECT_EQ(sr2NextIntegrationTime(3, 65535, 14000, 18000), 0);
}
