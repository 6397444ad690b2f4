// The board geometry's frame made in the shared memory's slots
// (ShmFrameSink::publishBoard, issue 29 §2) against the path it replaces,
// kept here as the reference: the compositor's images copied into the
// slots (publishComposite + publishBoardLecturer). A reader gets the same
// bytes from both, frame after frame, with repeated and board-only frames
// between.
#include "algo/board_compositor.hpp"
#include "algo/composite.hpp"
#include "hal/depthkey_shm.h"
#include "hal/shm_frame_sink.hpp"
#include "tests/shm_test_util.hpp"

#include <gtest/gtest.h>

#include <vector>

using namespace depthkey;
using depthkey::test::ShmName;

namespace {

constexpr int kCw = 80, kCh = 60, kBw = 150, kBh = 100;

struct Names {
	ShmName composite, lecturer, boardLecturer;
	OutputSettings settings(int slots) const
	{
		OutputSettings s;
		s.compositeName = composite.str();
		s.lecturerName = lecturer.str();
		s.boardLecturerName = boardLecturer.str();
		s.slots = slots;
		return s;
	}
};

Homography tiltedView()
{
	Homography h;
	h.h = { 1.7, 0.12, 8.0, -0.05, 1.6, 5.0, 0.0009, -0.0006, 1.0 };
	return h;
}

RgbImage boardPicture(int seed)
{
	RgbImage board(kBw, kBh);
	for (int y = 0; y < kBh; ++y)
		for (int x = 0; x < kBw; ++x)
			board.at(x, y) = { uint8_t(x * seed), uint8_t(y * 3 + seed), uint8_t(x ^ y) };
	return board;
}

// The camera-geometry lecturer layer of a box that walks across the view.
RgbaImage layerAt(int frame, Roi &box)
{
	RgbImage colour(kCw, kCh);
	Gray8Image alpha(kCw, kCh, 0);
	box = { 2 + 4 * frame % 50, 3 + 3 * (frame % 4), std::min(kCw, 22 + 4 * frame % 50), 25 + 3 * (frame % 4) };
	for (int y = 0; y < kCh; ++y)
		for (int x = 0; x < kCw; ++x) {
			colour.at(x, y) = { uint8_t(3 * x), uint8_t(4 * y), uint8_t(x * y) };
			if (x >= box.x0 && x < box.x1 && y >= box.y0 && y < box.y1)
				alpha.at(x, y) = uint8_t(64 | (x * 37 + y * 11));
		}
	RgbaImage layer;
	lecturerLayer(colour, alpha, layer, KernelPath::C);
	return layer;
}

std::vector<uint8_t> readLatest(const std::string &name, dk_shm_frame_info &info)
{
	dk_shm_reader r;
	if (dk_shm_open(name.c_str(), &r))
		return {};
	std::vector<uint8_t> out(r.frame_bytes);
	if (dk_shm_read_latest(&r, out.data(), out.size(), &info))
		out.clear();
	dk_shm_close(&r);
	return out;
}

// Both streams of both sinks as a reader gets them: the same bytes, stamps
// and flags.
void expectSameFrames(const Names &made, const Names &copied, int frame)
{
	for (auto stream : { &Names::composite, &Names::boardLecturer }) {
		dk_shm_frame_info madeInfo{}, copiedInfo{};
		const auto madeBytes = readLatest((made.*stream).str(), madeInfo);
		const auto copiedBytes = readLatest((copied.*stream).str(), copiedInfo);
		ASSERT_FALSE(copiedBytes.empty()) << "frame " << frame;
		EXPECT_TRUE(madeBytes == copiedBytes) << (made.*stream).str() << ", frame " << frame;
		EXPECT_EQ(madeInfo.frame, copiedInfo.frame) << frame;
		EXPECT_EQ(madeInfo.timestamp_ns, copiedInfo.timestamp_ns) << frame;
		EXPECT_EQ(madeInfo.flags, copiedInfo.flags) << frame;
	}
}

} // namespace

TEST(ShmFrameSink, BoardFramesMadeInTheSlotsAreWhatTheCopiedImagesWere)
{
	for (int slots : { 2, 3 }) {
		Names made, copied;
		ShmFrameSink madeSink, copiedSink;
		ASSERT_EQ(madeSink.open(made.settings(slots), kCw, kCh, kBw, kBh), 0) << madeSink.describeError();
		ASSERT_EQ(copiedSink.open(copied.settings(slots), kCw, kCh, kBw, kBh), 0);
		BoardCompositor inPlace, reference;
		ASSERT_TRUE(inPlace.configure(tiltedView(), kCw, kCh, kBw, kBh));
		ASSERT_TRUE(reference.configure(tiltedView(), kCw, kCh, kBw, kBh));
		RgbImage board = boardPicture(3), composite;
		RgbaImage boardLayer;
		const Gray8Image alpha(kCw, kCh, 0);
		for (int frame = 1; frame <= 14; ++frame) {
			const uint64_t stamp = 1000u * frame;
			const uint32_t flags = DK_SHM_FLAG_ONLINE | DK_SHM_FLAG_COLOUR_OK | DK_SHM_FLAG_DEPTH_OK;
			// The camera-geometry layer, as every frame has (repeatLast() repeats it too).
			for (ShmFrameSink *sink : { &madeSink, &copiedSink }) {
				if (frame != 6 && frame != 7) {
					ASSERT_EQ(sink->publishLecturer(nullptr, alpha, stamp, flags), 0);
				}
			}
			if (frame == 6 || frame == 7) { // shed frames: the last one again
				ASSERT_EQ(madeSink.repeatLast(stamp, flags | DK_SHM_FLAG_REPEATED), 0);
				ASSERT_EQ(copiedSink.repeatLast(stamp, flags | DK_SHM_FLAG_REPEATED), 0);
			} else if (frame == 10) { // no depth: the board alone, from images (BoardOutput::showBoardOnly)
				const RgbaImage clear(kBw, kBh, Rgba8{ 0, 0, 0, 0 });
				for (ShmFrameSink *sink : { &madeSink, &copiedSink }) {
					ASSERT_EQ(sink->publishComposite(board, stamp, DK_SHM_FLAG_COLOUR_OK), 0);
					ASSERT_EQ(sink->publishBoardLecturer(clear, stamp, DK_SHM_FLAG_COLOUR_OK), 0);
				}
				// The slot so written is known to hold no frame of inPlace's.
			} else {
				if (frame == 4) { // a new board picture
					board = boardPicture(7);
					inPlace.forgetBoard();
					reference.forgetBoard();
				}
				Roi box;
				const RgbaImage layer = layerAt(frame, box);
				ComposedBoardFrame maker;
				maker.compositor = &inPlace;
				maker.layer = &layer;
				maker.roi = box;
				maker.board = &board;
				maker.opacityQ8 = 200;
				ASSERT_EQ(madeSink.publishBoard(maker, stamp, flags), 0) << madeSink.describeError();
				reference.compose(layer, box, board, 200, composite, boardLayer);
				ASSERT_EQ(copiedSink.publishComposite(composite, stamp, flags), 0);
				ASSERT_EQ(copiedSink.publishBoardLecturer(boardLayer, stamp, flags), 0);
			}
			expectSameFrames(made, copied, frame);
			if (HasFailure())
				return;
		}
	}
}

// In camera geometry there is no board stream: nothing is lent, the
// composite's newest frame stays what it was.
TEST(ShmFrameSink, BoardFrameWithoutABoardStreamLeavesTheCompositeAsItWas)
{
	Names names;
	ShmFrameSink sink;
	ASSERT_EQ(sink.open(names.settings(2), kCw, kCh), 0);
	const RgbImage composite(kCw, kCh, Rgb8{ 4, 5, 6 });
	ASSERT_EQ(sink.publishComposite(composite, 1, 0), 0);
	BoardCompositor compositor;
	ASSERT_TRUE(compositor.configure(tiltedView(), kCw, kCh, kBw, kBh));
	Roi box;
	const RgbaImage layer = layerAt(1, box);
	const RgbImage board = boardPicture(2);
	ComposedBoardFrame maker;
	maker.compositor = &compositor;
	maker.layer = &layer;
	maker.roi = box;
	maker.board = &board;
	EXPECT_EQ(sink.publishBoard(maker, 2, 0), -EBADF);
	dk_shm_frame_info info{};
	const auto bytes = readLatest(names.composite.str(), info);
	EXPECT_EQ(info.frame, 1u);
	EXPECT_EQ(info.timestamp_ns, 1u);
	const auto *first = reinterpret_cast<const uint8_t *>(composite.data());
	EXPECT_TRUE(bytes == std::vector<uint8_t>(first, first + composite.size() * sizeof(Rgb8)));
}
