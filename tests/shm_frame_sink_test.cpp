// ShmFrameSink: the daemon's output, read back through the C reader.
#include "algo/composite.hpp"
#include "hal/depthkey_shm.h"
#include "hal/shm_frame_sink.hpp"
#include "tests/shm_test_util.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <vector>

using namespace depthkey;
using depthkey::test::ShmName;

namespace {

struct SinkNames {
	ShmName composite;
	ShmName lecturer;
	ShmName boardLecturer;
	OutputSettings settings() const
	{
		OutputSettings s;
		s.compositeName = composite.str();
		s.lecturerName = lecturer.str();
		s.boardLecturerName = boardLecturer.str();
		s.slots = 3;
		return s;
	}
};

RgbImage rgbPattern(int width, int height)
{
	RgbImage image(width, height);
	for (int y = 0; y < height; y++)
		for (int x = 0; x < width; x++)
			image.at(x, y) = { uint8_t(x * 5), uint8_t(y * 9), uint8_t(x + y) };
	return image;
}

Gray8Image alphaPattern(int width, int height)
{
	Gray8Image image(width, height);
	for (int y = 0; y < height; y++)
		for (int x = 0; x < width; x++)
			image.at(x, y) = uint8_t(x * y + 7 * x);
	return image;
}

// Reads the newest frame of `name`; returns the bytes or an empty vector.
std::vector<uint8_t> readLatest(const std::string &name, dk_shm_frame_info *info)
{
	dk_shm_reader r;
	if (dk_shm_open(name.c_str(), &r))
		return {};
	std::vector<uint8_t> out(r.frame_bytes);
	if (dk_shm_read_latest(&r, out.data(), out.size(), info))
		out.clear();
	dk_shm_close(&r);
	return out;
}

} // namespace

TEST(ShmFrameSink, PublishesBothStreams)
{
	SinkNames names;
	ShmFrameSink sink;
	ASSERT_EQ(sink.open(names.settings(), 40, 30), 0) << sink.describeError();

	const RgbImage composite = rgbPattern(40, 30);
	const Gray8Image alpha = alphaPattern(40, 30);
	const uint32_t flags = DK_SHM_FLAG_ONLINE | DK_SHM_FLAG_COLOUR_OK | DK_SHM_FLAG_DEPTH_OK;
	ASSERT_EQ(sink.publishComposite(composite, 123456789, flags), 0);
	// The layer is made in the slot from the colour frame and its alpha: the
	// same bytes as the C reference makes into an image of its own.
	ASSERT_EQ(sink.publishLecturer(&composite, alpha, 123456789, DK_SHM_FLAG_COLOUR_OK), 0);
	RgbaImage lecturer;
	lecturerLayer(composite, alpha, lecturer, KernelPath::C);

	dk_shm_frame_info info{};
	auto bytes = readLatest(names.composite.str(), &info);
	ASSERT_EQ(bytes.size(), 40u * 30 * 3);
	EXPECT_EQ(std::memcmp(bytes.data(), composite.data(), bytes.size()), 0);
	EXPECT_EQ(info.fourcc, DK_SHM_FORMAT_RGB24);
	EXPECT_EQ(info.timestamp_ns, 123456789u);
	EXPECT_EQ(info.flags, flags);

	bytes = readLatest(names.lecturer.str(), &info);
	ASSERT_EQ(bytes.size(), 40u * 30 * 4);
	EXPECT_EQ(std::memcmp(bytes.data(), lecturer.data(), bytes.size()), 0);
	EXPECT_EQ(info.fourcc, DK_SHM_FORMAT_RGBA32);
	EXPECT_EQ(info.flags, DK_SHM_FLAG_COLOUR_OK);
	EXPECT_EQ(sink.describeError(), "");

	// NO SIGNAL: no colour frame, the layer transparent black.
	ASSERT_EQ(sink.publishLecturer(nullptr, alpha, 987654321, 0), 0);
	bytes = readLatest(names.lecturer.str(), &info);
	ASSERT_EQ(bytes.size(), 40u * 30 * 4);
	EXPECT_EQ(std::count(bytes.begin(), bytes.end(), uint8_t(0)), ptrdiff_t(bytes.size()));
	EXPECT_EQ(info.timestamp_ns, 987654321u);
}

// The composite made in its slot from its parts: the bytes compositeRoi()
// makes, with a whole board and a one-row (solid) board; parts of another
// size are refused, not read past.
TEST(ShmFrameSink, MakesTheCompositeFromItsPartsInTheSlot)
{
	SinkNames names;
	ShmFrameSink sink;
	ASSERT_EQ(sink.open(names.settings(), 40, 30), 0) << sink.describeError();
	const RgbImage colour = rgbPattern(40, 30);
	Gray8Image alpha(40, 30, 0);
	for (int y = 5; y < 20; y++)
		for (int x = 7; x < 31; x++)
			alpha.at(x, y) = uint8_t(x * 9 + y);
	RgbImage wholeBoard(40, 30), solidBoard(40, 1, Rgb8{ 10, 200, 30 });
	for (int y = 0; y < 30; y++)
		for (int x = 0; x < 40; x++)
			wholeBoard.at(x, y) = { uint8_t(255 - x), uint8_t(y * 7), 90 };
	for (const RgbImage *board : { &wholeBoard, &solidBoard }) {
		const CompositeInputs in{ &colour, &alpha, board, Roi{ 7, 5, 31, 20 }, 180, bestKernelPath() };
		ASSERT_EQ(sink.publishComposite(in, 42, DK_SHM_FLAG_ONLINE), 0) << sink.describeError();
		RgbImage expected;
		compositeRoi(colour, alpha, *board, in.roi, 180, expected, KernelPath::C);
		dk_shm_frame_info info{};
		const auto bytes = readLatest(names.composite.str(), &info);
		ASSERT_EQ(bytes.size(), 40u * 30 * 3);
		EXPECT_EQ(std::memcmp(bytes.data(), expected.data(), bytes.size()), 0) << board->height();
		EXPECT_EQ(info.timestamp_ns, 42u);
	}
	const Gray8Image smallAlpha(16, 16, 0);
	const CompositeInputs bad{ &colour, &smallAlpha, &wholeBoard, Roi{}, 256, KernelPath::C };
	EXPECT_EQ(sink.publishComposite(bad, 0, 0), -EINVAL);
	EXPECT_NE(sink.describeError().find("16x16"), std::string::npos) << sink.describeError();
	const RgbImage smallBoard(20, 30);
	const CompositeInputs badBoard{ &colour, &alpha, &smallBoard, Roi{}, 256, KernelPath::C };
	EXPECT_EQ(sink.publishComposite(badBoard, 0, 0), -EINVAL);
}

// Each stream's readers are counted apart, the board-geometry layer's too
// (a recorder rendering the board's strokes itself reads only that one).
TEST(ShmFrameSink, CountsTheReadersOfEachStream)
{
	SinkNames names;
	ShmFrameSink sink;
	ASSERT_EQ(sink.open(names.settings(), 40, 30, 64, 36), 0) << sink.describeError();
	EXPECT_EQ(sink.countReaders(1'000'000'000), (ReaderCounts{ 0, 0, 0 }));
	dk_shm_reader board, composite;
	ASSERT_EQ(dk_shm_open(names.boardLecturer.c_str(), &board), 0);
	ASSERT_EQ(dk_shm_open(names.composite.c_str(), &composite), 0);
	ReaderCounts counts = sink.countReaders(1'000'000'000);
	EXPECT_EQ(counts, (ReaderCounts{ 1, 0, 1 }));
	EXPECT_EQ(counts.total(), 2);
	dk_shm_close(&board);
	EXPECT_EQ(sink.countReaders(1'000'000'000), (ReaderCounts{ 1, 0, 0 }));
	dk_shm_close(&composite);
	sink.close();
}

TEST(ShmFrameSink, WrongImageSizeNamesTheStream)
{
	SinkNames names;
	ShmFrameSink sink;
	EXPECT_EQ(sink.publishComposite(rgbPattern(8, 8), 0, 0), -EBADF);
	ASSERT_EQ(sink.open(names.settings(), 40, 30), 0);
	const RgbImage small = rgbPattern(16, 16);
	EXPECT_EQ(sink.publishLecturer(&small, alphaPattern(16, 16), 0, 0), -EINVAL);
	std::string message = sink.describeError();
	EXPECT_NE(message.find(names.lecturer.str()), std::string::npos) << message;
	EXPECT_NE(message.find("16x16"), std::string::npos) << message;
	// A colour frame of another size than its alpha is refused too, not read past.
	EXPECT_EQ(sink.publishLecturer(&small, alphaPattern(40, 30), 0, 0), -EINVAL);
	message = sink.describeError();
	EXPECT_NE(message.find("16x16"), std::string::npos) << message;
	sink.close();
	const RgbImage right = rgbPattern(40, 30);
	EXPECT_EQ(sink.publishLecturer(&right, alphaPattern(40, 30), 0, 0), -EBADF);
}

TEST(ShmFrameSink, FailedOpenNamesTheObject)
{
	SinkNames names;
	ShmFrameSink sink;
	OutputSettings settings = names.settings();
	settings.group = "depthkey-no-such-group";
	EXPECT_EQ(sink.open(settings, 40, 30), -ENOENT);
	const std::string message = sink.describeError();
	EXPECT_NE(message.find(names.composite.str()), std::string::npos) << message;
	EXPECT_NE(message.find("depthkey-no-such-group"), std::string::npos) << message;
	EXPECT_EQ(sink.publishComposite(rgbPattern(40, 30), 0, 0), -EBADF);
}

// A config reload may change the resolution: readers see a new generation.
TEST(ShmFrameSink, ReopenWithNewSize)
{
	SinkNames names;
	ShmFrameSink sink;
	ASSERT_EQ(sink.open(names.settings(), 40, 30), 0);
	ASSERT_EQ(sink.publishComposite(rgbPattern(40, 30), 1, 0), 0);
	dk_shm_reader r;
	ASSERT_EQ(dk_shm_open(names.composite.c_str(), &r), 0);

	ASSERT_EQ(sink.open(names.settings(), 64, 48), 0) << sink.describeError();
	std::vector<uint8_t> out(r.frame_bytes);
	EXPECT_EQ(dk_shm_read_latest(&r, out.data(), out.size(), nullptr), -ESTALE);
	dk_shm_close(&r);

	const RgbImage bigger = rgbPattern(64, 48);
	ASSERT_EQ(sink.publishComposite(bigger, 2, 0), 0);
	dk_shm_frame_info info{};
	auto bytes = readLatest(names.composite.str(), &info);
	ASSERT_EQ(bytes.size(), 64u * 48 * 3);
	EXPECT_EQ(info.width, 64u);
	EXPECT_EQ(std::memcmp(bytes.data(), bigger.data(), bytes.size()), 0);

	sink.close();
	bytes = readLatest(names.composite.str(), &info);
	ASSERT_FALSE(bytes.empty());
	EXPECT_EQ(info.online, 0u);
}
