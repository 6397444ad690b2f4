// Reader presence in the shared-memory ring (hal/depthkey_shm.h, version 3):
// readers beat in their slot, ShmRingWriter::countReaders() counts them, a
// reader that stops or dies is counted gone and its slot freed, a clean
// close is gone at once, and a reader without write access still reads.
#include "hal/depthkey_shm.h"
#include "hal/shm_ring_writer.hpp"
#include "tests/shm_test_util.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <ctime>
#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <thread>
#include <vector>

using namespace depthkey;
using depthkey::test::ShmName;

namespace {

constexpr uint64_t kSecond = 1'000'000'000u;
constexpr uint64_t kTimeoutNs = uint64_t{ DK_SHM_READER_TIMEOUT_MS } * 1'000'000u;

uint64_t monotonicNs()
{
	timespec ts{};
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return static_cast<uint64_t>(ts.tv_sec) * kSecond + static_cast<uint64_t>(ts.tv_nsec);
}

class ReaderPresence : public ::testing::Test
{
protected:
	void SetUp() override
	{
		ASSERT_EQ(writer_.open(name_.str(), 8, 4, DK_SHM_FORMAT_RGB24, 3, ""), 0)
			<< writer_.describeError();
		std::vector<uint8_t> pixels(8 * 4 * 3, 7);
		ASSERT_EQ(writer_.write(pixels.data(), 8 * 3, 1, 0), 0);
	}

	ShmName name_;
	ShmRingWriter writer_;
};

} // namespace

TEST_F(ReaderPresence, OpenReadersAreCountedAndACleanCloseIsGoneAtOnce)
{
	EXPECT_EQ(writer_.countReaders(10 * kSecond), 0);
	dk_shm_reader a, b;
	ASSERT_EQ(dk_shm_open(name_.c_str(), &a), 0);
	EXPECT_EQ(a.presence_error, 0);
	EXPECT_EQ(writer_.countReaders(10 * kSecond), 1);
	ASSERT_EQ(dk_shm_open(name_.c_str(), &b), 0);
	EXPECT_NE(a.presence_index, b.presence_index);
	EXPECT_NE(a.presence_token, b.presence_token);
	EXPECT_EQ(writer_.countReaders(10 * kSecond), 2);
	dk_shm_close(&a);
	EXPECT_EQ(writer_.countReaders(10 * kSecond), 1);
	dk_shm_close(&b);
	EXPECT_EQ(writer_.countReaders(10 * kSecond), 0);
}

TEST_F(ReaderPresence, AReaderThatStopsBeatingIsGoneAfterTheTimeoutAndComesBackWhenItReads)
{
	dk_shm_reader r;
	ASSERT_EQ(dk_shm_open(name_.c_str(), &r), 0);
	const uint64_t t0 = 100 * kSecond;
	EXPECT_EQ(writer_.countReaders(t0), 1);
	EXPECT_EQ(writer_.countReaders(t0 + kTimeoutNs), 1) << "still within the timeout";
	EXPECT_EQ(writer_.countReaders(t0 + kTimeoutNs + 1), 0) << "silent longer than the timeout";
	EXPECT_EQ(__atomic_load_n(&r.presence->readers[r.presence_index].owner, __ATOMIC_RELAXED), 0u)
		<< "the writer freed the slot";

	// It reads again: it notices the lost slot and claims one anew.
	std::vector<uint8_t> frame(r.frame_bytes);
	ASSERT_EQ(dk_shm_read_latest(&r, frame.data(), frame.size(), nullptr), 0);
	EXPECT_EQ(r.presence_error, 0);
	EXPECT_EQ(writer_.countReaders(t0 + 2 * kTimeoutNs), 1);
	// Beats keep it counted however long it lives.
	for (uint64_t t = t0 + 2 * kTimeoutNs; t < t0 + 10 * kTimeoutNs; t += kTimeoutNs / 2) {
		uint64_t latest;
		ASSERT_EQ(dk_shm_latest(&r, &latest), 0);
		EXPECT_EQ(writer_.countReaders(t), 1) << t;
	}
	EXPECT_EQ(__atomic_load_n(&r.presence->readers[r.presence_index].frames_read, __ATOMIC_RELAXED), 1u);
	dk_shm_close(&r);
}

TEST_F(ReaderPresence, AKilledReaderProcessIsCountedGoneWithinTwoSeconds)
{
	int ready[2];
	ASSERT_EQ(pipe(ready), 0);
	pid_t child = fork();
	ASSERT_GE(child, 0);
	if (child == 0) {
		dk_shm_reader r;
		if (dk_shm_open(name_.c_str(), &r) != 0 || r.presence_error)
			_exit(1);
		char c = 'r';
		if (write(ready[1], &c, 1) != 1)
			_exit(1);
		for (;;) { // a recorder polling for frames
			uint64_t latest;
			dk_shm_latest(&r, &latest);
			usleep(2000);
		}
	}
	close(ready[1]);
	char c = 0;
	ASSERT_EQ(read(ready[0], &c, 1), 1);
	close(ready[0]);
	// Sampled every 250 ms as the daemon does.
	for (int i = 0; i < 6; i++) {
		EXPECT_EQ(writer_.countReaders(monotonicNs()), 1) << "sample " << i;
		std::this_thread::sleep_for(std::chrono::milliseconds(250));
	}
	kill(child, SIGKILL);
	int status;
	waitpid(child, &status, 0);
	const uint64_t killedAt = monotonicNs();
	uint64_t goneAfter = 0;
	while (monotonicNs() - killedAt < 3 * kSecond) {
		if (writer_.countReaders(monotonicNs()) == 0) {
			goneAfter = monotonicNs() - killedAt;
			break;
		}
		std::this_thread::sleep_for(std::chrono::milliseconds(250));
	}
	ASSERT_GT(goneAfter, 0u) << "the dead reader was still counted after 3 s";
	EXPECT_LE(goneAfter, 2 * kSecond);
	EXPECT_GE(goneAfter, kTimeoutNs / 2) << "counted gone before its beats could have stopped";
}

TEST_F(ReaderPresence, TheSeventeenthReaderReadsButIsNotCounted)
{
	std::vector<dk_shm_reader> readers(DK_SHM_MAX_READERS + 1);
	for (dk_shm_reader &r : readers)
		ASSERT_EQ(dk_shm_open(name_.c_str(), &r), 0);
	EXPECT_EQ(readers.back().presence_error, -EBUSY);
	EXPECT_EQ(writer_.countReaders(5 * kSecond), static_cast<int>(DK_SHM_MAX_READERS));
	std::vector<uint8_t> frame(readers.back().frame_bytes);
	EXPECT_EQ(dk_shm_read_latest(&readers.back(), frame.data(), frame.size(), nullptr), 0);
	// A slot frees up: the uncounted reader takes it on its next beat.
	dk_shm_close(&readers.front());
	EXPECT_EQ(dk_shm_heartbeat(&readers.back()), 0);
	EXPECT_EQ(writer_.countReaders(5 * kSecond), static_cast<int>(DK_SHM_MAX_READERS));
	for (dk_shm_reader &r : readers)
		dk_shm_close(&r);
	EXPECT_EQ(writer_.countReaders(5 * kSecond), 0);
}

TEST_F(ReaderPresence, AReaderWithoutWriteAccessReadsUncounted)
{
	// root may write anything, so the child drops to nobody (the frames are
	// then made readable by others); otherwise the presence object is made
	// read-only to us.
	const bool root = geteuid() == 0;
	int fd = shm_open(root ? name_.c_str() : name_.presence().c_str(), O_RDWR, 0);
	ASSERT_GE(fd, 0);
	ASSERT_EQ(fchmod(fd, root ? 0644 : 0440), 0);
	close(fd);

	pid_t child = fork();
	ASSERT_GE(child, 0);
	if (child == 0) {
		if (root && (setgid(65534) != 0 || setuid(65534) != 0))
			_exit(3);
		dk_shm_reader r;
		if (dk_shm_open(name_.c_str(), &r) != 0)
			_exit(1);
		std::vector<uint8_t> frame(r.frame_bytes);
		int read = dk_shm_read_latest(&r, frame.data(), frame.size(), nullptr);
		_exit(read == 0 && r.presence_error == -EACCES && !r.presence ? 0 : 2);
	}
	int status = 0;
	waitpid(child, &status, 0);
	ASSERT_TRUE(WIFEXITED(status));
	EXPECT_EQ(WEXITSTATUS(status), 0) << "1: open failed, 2: not read or wrongly counted, 3: setuid";
	EXPECT_EQ(writer_.countReaders(5 * kSecond), 0);
}

TEST_F(ReaderPresence, ARestartedWriterForgetsTheOldReaders)
{
	dk_shm_reader r;
	ASSERT_EQ(dk_shm_open(name_.c_str(), &r), 0);
	EXPECT_EQ(writer_.countReaders(kSecond), 1);
	ASSERT_EQ(writer_.open(name_.str(), 8, 4, DK_SHM_FORMAT_RGB24, 3, ""), 0);
	EXPECT_EQ(writer_.countReaders(kSecond), 0);
	uint64_t latest;
	EXPECT_EQ(dk_shm_latest(&r, &latest), -ESTALE);
	dk_shm_close(&r);
	ASSERT_EQ(dk_shm_open(name_.c_str(), &r), 0);
	EXPECT_EQ(writer_.countReaders(kSecond), 1);
	dk_shm_close(&r);
}

TEST_F(ReaderPresence, ABadPresenceTableIsRefused)
{
	int fd = shm_open(name_.c_str(), O_RDWR, 0);
	ASSERT_GE(fd, 0);
	void *map = mmap(nullptr, sizeof(dk_shm_header), PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
	close(fd);
	ASSERT_NE(map, MAP_FAILED);
	auto *h = static_cast<dk_shm_header *>(map);
	const uint64_t offset = h->reader_offset;
	const uint32_t slots = h->reader_slots;
	EXPECT_EQ(offset % DK_SHM_DATA_ALIGN, 0u);

	h->reader_offset = offset + 8; // not on a page
	EXPECT_EQ(depthkey::test::openStatus(name_.c_str()), -EPROTO);
	h->reader_offset = offset + DK_SHM_DATA_ALIGN; // past the presence object: read, uncounted
	dk_shm_reader r;
	ASSERT_EQ(dk_shm_open(name_.c_str(), &r), 0);
	EXPECT_EQ(r.presence_error, -EPROTO);
	EXPECT_EQ(r.presence, nullptr);
	dk_shm_close(&r);
	h->reader_offset = offset;
	h->reader_slots = DK_SHM_MAX_READERS + 1;
	EXPECT_EQ(depthkey::test::openStatus(name_.c_str()), -EPROTO);
	h->reader_slots = slots;
	h->version = 2; // a version-2 writer's object: the table inside it, group-writable
	EXPECT_EQ(depthkey::test::openStatus(name_.c_str()), -EPROTO);
	h->version = DK_SHM_VERSION;
	EXPECT_EQ(depthkey::test::openStatus(name_.c_str()), 0);
	munmap(map, sizeof(dk_shm_header));
}

// Issue 31: the presence object is the one thing a reader may write; one
// that shrinks it to nothing neither faults the writer (it never maps it)
// nor stops counting for good: the size is restored, reported by the next
// write(), and readers claim slots again.
TEST_F(ReaderPresence, AShrunkPresenceObjectIsRestored)
{
	dk_shm_reader r;
	ASSERT_EQ(dk_shm_open(name_.c_str(), &r), 0);
	ASSERT_EQ(writer_.countReaders(kSecond), 1);
	int fd = shm_open(name_.presence().c_str(), O_RDWR, 0);
	ASSERT_GE(fd, 0);
	ASSERT_EQ(ftruncate(fd, 0), 0);
	EXPECT_EQ(writer_.countReaders(2 * kSecond), 0);
	struct stat st{};
	ASSERT_EQ(fstat(fd, &st), 0);
	close(fd);
	EXPECT_GE(static_cast<size_t>(st.st_size), sizeof(dk_shm_reader_table));
	std::vector<uint8_t> pixels(8 * 4 * 3, 9);
	EXPECT_EQ(writer_.write(pixels.data(), 8 * 3, 2, 0), -EUCLEAN);
	EXPECT_NE(writer_.describeError().find(name_.presence() + ": 0 bytes"), std::string::npos)
		<< writer_.describeError();
	EXPECT_EQ(writer_.write(pixels.data(), 8 * 3, 3, 0), 0); // reported once
	EXPECT_EQ(dk_shm_heartbeat(&r), 0); // its slot was zeroed: claims one again
	EXPECT_EQ(writer_.countReaders(3 * kSecond), 1);
	dk_shm_close(&r);
}
