// ShmRingWriter's lent slots (issue 29 §2: a frame written in place): a
// reader sees each committed frame whole, never a lent slot before its
// commit nor an abandoned one, and each slot's tag goes with its pixels.
#include "hal/depthkey_shm.h"
#include "hal/shm_ring_writer.hpp"
#include "tests/shm_test_util.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cstring>
#include <thread>
#include <vector>

using namespace depthkey;
using depthkey::test::ShmName;

namespace {

constexpr int kWidth = 8, kHeight = 4, kBytes = kWidth * kHeight * 3;

// The newest frame as a reader gets it: its first byte, or -1 and errno.
struct Seen {
	int ret = 0;
	uint64_t frame = 0;
	std::vector<uint8_t> bytes;
};
Seen readNewest(dk_shm_reader &r)
{
	Seen seen;
	seen.bytes.resize(r.frame_bytes);
	dk_shm_frame_info info{};
	seen.ret = dk_shm_read_latest(&r, seen.bytes.data(), seen.bytes.size(), &info);
	seen.frame = info.frame;
	return seen;
}

} // namespace

TEST(ShmRingLend, ALentSlotIsSeenOnlyOnceCommittedAndAnAbandonedOneNever)
{
	ShmName name;
	ShmRingWriter writer;
	ASSERT_EQ(writer.open(name.str(), kWidth, kHeight, DK_SHM_FORMAT_RGB24, 2, ""), 0);
	dk_shm_reader r;
	ASSERT_EQ(dk_shm_open(name.c_str(), &r), 0);

	// Before any frame: a lent slot is no frame.
	ShmRingWriter::LentSlot slot;
	ASSERT_EQ(writer.lend(slot, 1, 0), 0);
	EXPECT_EQ(slot.stride, kWidth * 3);
	std::memset(slot.pixels, 0x11, kBytes);
	EXPECT_EQ(readNewest(r).ret, -ENODATA);
	writer.commit(0);
	Seen seen = readNewest(r);
	ASSERT_EQ(seen.ret, 0);
	EXPECT_EQ(seen.frame, 1u);
	EXPECT_EQ(seen.bytes, std::vector<uint8_t>(kBytes, 0x11));

	// Half written, then a failure: the reader keeps frame 1, whole.
	ASSERT_EQ(writer.lend(slot, 2, 0), 0);
	std::memset(slot.pixels, 0x22, kBytes / 2);
	seen = readNewest(r);
	EXPECT_EQ(seen.frame, 1u);
	EXPECT_EQ(seen.bytes, std::vector<uint8_t>(kBytes, 0x11));
	writer.abandon();
	seen = readNewest(r);
	EXPECT_EQ(seen.frame, 1u);
	EXPECT_EQ(seen.bytes, std::vector<uint8_t>(kBytes, 0x11));
	EXPECT_EQ(writer.frameCount(), 1u);

	// The same slot lent again and committed: frame 2.
	ASSERT_EQ(writer.lend(slot, 3, 0), 0);
	EXPECT_EQ(slot.holds, 0u); // abandoned: its contents unknown
	std::memset(slot.pixels, 0x33, kBytes);
	EXPECT_EQ(readNewest(r).frame, 1u);
	writer.commit(77);
	seen = readNewest(r);
	EXPECT_EQ(seen.frame, 2u);
	EXPECT_EQ(seen.bytes, std::vector<uint8_t>(kBytes, 0x33));
	dk_shm_close(&r);
}

// Each slot's tag comes back with it; a repeated frame copies the tag with
// the pixels; a frame from write() and a reopen forget them.
TEST(ShmRingLend, EachSlotsTagGoesWithItsPixels)
{
	ShmName name;
	ShmRingWriter writer;
	ASSERT_EQ(writer.open(name.str(), kWidth, kHeight, DK_SHM_FORMAT_RGB24, 2, ""), 0);
	ShmRingWriter::LentSlot slot;
	ASSERT_EQ(writer.lend(slot, 1, 0), 0); // frame 1, slot 1
	EXPECT_EQ(slot.holds, 0u);
	writer.commit(10);
	ASSERT_EQ(writer.lend(slot, 2, 0), 0); // frame 2, slot 0
	writer.commit(20);
	ASSERT_EQ(writer.lend(slot, 3, 0), 0); // frame 3, slot 1
	EXPECT_EQ(slot.holds, 10u);
	writer.commit(30);
	ASSERT_EQ(writer.repeatLast(4, DK_SHM_FLAG_REPEATED), 0); // frame 4, slot 0: frame 3's
	ASSERT_EQ(writer.lend(slot, 5, 0), 0); // frame 5, slot 1
	EXPECT_EQ(slot.holds, 30u);
	writer.commit(50);
	ASSERT_EQ(writer.lend(slot, 6, 0), 0); // frame 6, slot 0: the repeat of 3
	EXPECT_EQ(slot.holds, 30u);
	writer.abandon();
	const std::vector<uint8_t> pixels(kBytes, 1);
	ASSERT_EQ(writer.write(pixels.data(), kWidth * 3, 6, 0), 0); // frame 6, slot 0
	ASSERT_EQ(writer.lend(slot, 7, 0), 0); // frame 7, slot 1
	EXPECT_EQ(slot.holds, 50u);
	writer.commit(70);
	ASSERT_EQ(writer.lend(slot, 8, 0), 0); // frame 8, slot 0: write()'s
	EXPECT_EQ(slot.holds, 0u);
	writer.commit(80);
	ASSERT_EQ(writer.open(name.str(), kWidth, kHeight, DK_SHM_FORMAT_RGB24, 2, ""), 0);
	for (int frame = 1; frame <= 2; ++frame) {
		ASSERT_EQ(writer.lend(slot, frame, 0), 0);
		EXPECT_EQ(slot.holds, 0u) << frame;
		writer.commit(0);
	}
	// Closed: nothing lent.
	writer.close();
	EXPECT_EQ(writer.lend(slot, 9, 0), -EBADF);
}

// A reader racing the writer: every frame it gets is one committed frame,
// whole (all its bytes the frame number's), never a slot being made row by
// row.
TEST(ShmRingLend, AReaderRacingTheWriterSeesEachFrameWhole)
{
	ShmName name;
	ShmRingWriter writer;
	ASSERT_EQ(writer.open(name.str(), 64, 32, DK_SHM_FORMAT_RGBA32, 2, ""), 0);
	std::atomic<bool> done{ false };
	std::atomic<uint64_t> checked{ 0 }, torn{ 0 };
	std::thread reader([&] {
		dk_shm_reader r;
		if (dk_shm_open(name.c_str(), &r))
			return;
		std::vector<uint8_t> bytes(r.frame_bytes);
		while (!done.load()) {
			dk_shm_frame_info info{};
			if (dk_shm_read_latest(&r, bytes.data(), bytes.size(), &info))
				continue;
			const uint8_t want = uint8_t(info.timestamp_ns);
			for (uint8_t b : bytes)
				if (b != want) {
					torn++;
					break;
				}
			checked++;
		}
		dk_shm_close(&r);
	});
	for (uint64_t frame = 1; frame <= 3000 || checked.load() < 200; ++frame) {
		ShmRingWriter::LentSlot slot;
		ASSERT_EQ(writer.lend(slot, frame, 0), 0);
		for (int y = 0; y < 32; ++y) {
			std::memset(slot.pixels + size_t(y) * slot.stride, int(frame & 255), size_t(slot.stride));
			if (y == 16)
				std::this_thread::yield(); // half made: the reader's chance to look
		}
		if (frame % 7 == 0)
			writer.abandon(); // a failure mid-way: never seen
		else
			writer.commit(frame);
		if (frame > 1000000)
			break;
	}
	done = true;
	reader.join();
	EXPECT_GT(checked.load(), 0u);
	EXPECT_EQ(torn.load(), 0u);
}
