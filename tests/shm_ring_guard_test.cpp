// Issue 31 point 1: the writer survives its object being shrunk (no SIGBUS)
// and notices and rewrites a header someone scribbled on, reporting what had
// changed; readers then accept the stream again. The group can no longer do
// either (mode 0640, tests/process/daemon_shm_tamper_test.cpp); these are the
// owner's (or root's) writes, the writer's last line of defence.
#include "hal/depthkey_shm.h"
#include "hal/shm_ring_writer.hpp"
#include "tests/shm_test_util.hpp"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <functional>
#include <sys/mman.h>
#include <sys/stat.h>
#include <vector>

using namespace depthkey;
using depthkey::test::ShmName;

namespace {

constexpr int kWidth = 64, kHeight = 48, kStride = kWidth * 3;

// A frame whose bytes tell it apart from the last one.
std::vector<uint8_t> frameOf(uint8_t value)
{
	return std::vector<uint8_t>(static_cast<size_t>(kStride) * kHeight, value);
}

// A reader opening the stream now reads frame `value`'s pixels.
bool aReaderReads(const ShmName &name, uint8_t value)
{
	dk_shm_reader r;
	if (dk_shm_open(name.c_str(), &r) != 0)
		return false;
	std::vector<uint8_t> got(r.frame_bytes);
	const bool ok = dk_shm_read_latest(&r, got.data(), got.size(), nullptr) == 0 && got == frameOf(value);
	dk_shm_close(&r);
	return ok;
}

// The owner's fd, as a process of the daemon's uid (or root) would have it.
int ownerFd(const ShmName &name)
{
	return shm_open(name.c_str(), O_RDWR, 0);
}

// Scribbles on the header through a mapping of its own, then checks the
// writer repairs it at its next frame and names the field.
void expectRepaired(const char *field, const std::function<void(dk_shm_header &)> &scribble)
{
	SCOPED_TRACE(field);
	ShmName name;
	ShmRingWriter writer;
	ASSERT_EQ(writer.open(name.str(), kWidth, kHeight, DK_SHM_FORMAT_RGB24, 3, ""), 0);
	ASSERT_EQ(writer.write(frameOf(1).data(), kStride, 1, 0), 0);
	const int fd = ownerFd(name);
	ASSERT_GE(fd, 0);
	void *map = mmap(nullptr, sizeof(dk_shm_header), PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
	close(fd);
	ASSERT_NE(map, MAP_FAILED);
	scribble(*static_cast<dk_shm_header *>(map));
	munmap(map, sizeof(dk_shm_header));

	const uint64_t generation = writer.generation();
	EXPECT_EQ(writer.write(frameOf(2).data(), kStride, 2, 0), -EUCLEAN);
	const std::string message = writer.describeError();
	EXPECT_NE(message.find(name.str() + ": rewrote the header, field '" + field), std::string::npos) << message;
	EXPECT_NE(writer.generation(), generation); // readers that opened meanwhile re-open
	EXPECT_TRUE(aReaderReads(name, 2));
	EXPECT_EQ(writer.write(frameOf(3).data(), kStride, 3, 0), 0); // repaired once
	EXPECT_TRUE(aReaderReads(name, 3));
}

} // namespace

// The two: every reader refused the stream while the daemon
// published and reported no error.
TEST(ShmRingGuard, AZeroedGenerationIsRewritten)
{
	expectRepaired("generation", [](dk_shm_header &h) { h.generation = 0; });
}

TEST(ShmRingGuard, ASlotCountOutOfRangeIsRewritten)
{
	expectRepaired("slot_count", [](dk_shm_header &h) { h.slot_count = 9; });
}

TEST(ShmRingGuard, EveryFieldReadersTrustIsChecked)
{
	expectRepaired("magic", [](dk_shm_header &h) { h.magic = 0; });
	expectRepaired("width", [](dk_shm_header &h) { h.width = 8; });
	expectRepaired("data_offset", [](dk_shm_header &h) { h.data_offset += 4096; });
	expectRepaired("latest_frame", [](dk_shm_header &h) { h.latest_frame = 7; });
	expectRepaired("reader_offset", [](dk_shm_header &h) { h.reader_offset = 4096; });
	expectRepaired("slots[2].sequence", [](dk_shm_header &h) { h.slots[2].sequence |= 1; });
}

// The SIGBUS: a frame written into an object shrunk to 0 (or to one
// page) faulted the writer. In a child, so that the fault fails this test
// rather than ending the run.
TEST(ShmRingGuard, AShrunkObjectIsResizedNotAFault)
{
	for (off_t size : { off_t{ 0 }, off_t{ 4096 } }) {
		SCOPED_TRACE(size);
		// Returns rather than exits, so that the objects are removed.
		auto shrinkAndWrite = [size]() {
			ShmName name;
			ShmRingWriter writer;
			if (writer.open(name.str(), kWidth, kHeight, DK_SHM_FORMAT_RGB24, 3, "") != 0 ||
			    writer.write(frameOf(1).data(), kStride, 1, 0) != 0)
				return 1;
			const int fd = ownerFd(name);
			if (fd < 0 || ftruncate(fd, size) != 0)
				return 2;
			// Frames 2 and 3 go to slots 2 and 0, past one page.
			if (writer.write(frameOf(2).data(), kStride, 2, 0) != -EUCLEAN)
				return 3;
			if (writer.describeError().find(name.str() + ": restored the size of the object '" +
							std::to_string(size) + " bytes") == std::string::npos)
				return 4;
			struct stat st{};
			fstat(fd, &st);
			close(fd);
			if (st.st_size <= 4096 || writer.write(frameOf(3).data(), kStride, 3, 0) != 0)
				return 5;
			return aReaderReads(name, 3) ? 0 : 6;
		};
		EXPECT_EXIT(_exit(shrinkAndWrite()), ::testing::ExitedWithCode(0), "")
			<< "1: open, 2: ftruncate, 3: not -EUCLEAN, 4: message, 5: not resized, 6: unreadable";
	}
}
