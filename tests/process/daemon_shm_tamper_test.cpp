// Issue 31 point 1, with the real depthkeyd: a reader in output.group (uid
// 65534, only the video group) tries what killed or silenced the stream
// before: opening the frames read-write, shrinking them (the daemon died of
// SIGBUS 0.10 s later) and writing 0 to the header's generation or 9 to its
// slot_count (every reader refused the stream while the daemon reported
// frames and no errors). Each is refused now; the one object it may write,
// its presence object, it shrinks, and the daemon restores it and says so.
// The owner's header writes are rewritten. The daemon keeps publishing and a
// reader of the group accepts the stream.
#include "tests/process/daemon_process.hpp"
#include "tests/shm_test_util.hpp"

#include <gtest/gtest.h>

#include <csignal>
#include <fcntl.h>
#include <grp.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <vector>

using namespace std::chrono_literals;
using depthkey::test::DaemonProcess;
using depthkey::test::openStatus;

namespace {

constexpr uid_t kNobody = 65534;

// In a child: uid 65534 with the output group alone.
bool becomeAReaderOfTheGroup(gid_t group)
{
	return setgroups(1, &group) == 0 && setgid(group) == 0 && setuid(kNobody) == 0;
}

// Bits of what the reader managed against one stream's object; 0 = nothing.
enum Harm : int {
	kOpenedReadWrite = 1,   // and then shrank it and wrote the header
	kShrankReadOnlyFd = 2,  // ftruncate through a read-only fd
	kMappedWritable = 4,    // a shared writable mapping of the frames
	kTruncatedByPath = 8,   // truncate(2) on /dev/shm/NAME
	kPresenceUnwritable = 16, // the one object it may write, it could not
};

int tryToHarm(const std::string &name)
{
	int harm = 0;
	int fd = shm_open(name.c_str(), O_RDWR, 0);
	if (fd >= 0) {
		// What the issue did: the header scribbled, then the object shrunk.
		harm |= kOpenedReadWrite;
		void *map = mmap(nullptr, sizeof(dk_shm_header), PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
		if (map != MAP_FAILED) {
			static_cast<dk_shm_header *>(map)->generation = 0;
			static_cast<dk_shm_header *>(map)->slot_count = 9;
			munmap(map, sizeof(dk_shm_header));
		}
		ftruncate(fd, 0);
		close(fd);
	}
	fd = shm_open(name.c_str(), O_RDONLY, 0);
	if (fd >= 0) {
		if (ftruncate(fd, 0) == 0)
			harm |= kShrankReadOnlyFd;
		void *map = mmap(nullptr, sizeof(dk_shm_header), PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
		if (map != MAP_FAILED)
			harm |= kMappedWritable;
		close(fd);
	}
	if (truncate(("/dev/shm" + name).c_str(), 4096) == 0)
		harm |= kTruncatedByPath;
	fd = shm_open((name + DK_SHM_PRESENCE_SUFFIX).c_str(), O_RDWR, 0);
	if (fd < 0 || ftruncate(fd, 0) != 0)
		harm |= kPresenceUnwritable;
	if (fd >= 0)
		close(fd);
	return harm;
}

// In a child of the group: reads `frames` frames, each newer than the last,
// counted as a reader. Exit status 0, or what failed.
int readAsTheGroup(const std::string &name, gid_t group, int frames)
{
	if (!becomeAReaderOfTheGroup(group))
		return 100;
	// Opened until counted: one that opens while its presence object is
	// still shrunk (the daemon restores it within 250 ms) reads uncounted.
	dk_shm_reader r;
	int ret = -EAGAIN;
	for (int tries = 0; tries < 100; tries++) {
		ret = dk_shm_open(name.c_str(), &r);
		if (ret == 0 && r.presence_error == 0)
			break;
		if (ret == 0)
			dk_shm_close(&r);
		usleep(20000);
	}
	if (ret)
		return 101;
	if (r.presence_error)
		return 102;
	std::vector<uint8_t> frame(r.frame_bytes);
	uint64_t last = 0;
	for (int got = 0, tries = 0; got < frames; tries++) {
		if (tries > 300)
			return 103;
		dk_shm_frame_info info{};
		ret = dk_shm_read_latest(&r, frame.data(), frame.size(), &info);
		if (ret == -ESTALE) { // a repair: a new generation
			dk_shm_close(&r);
			if (dk_shm_open(name.c_str(), &r) != 0)
				return 104;
			continue;
		}
		if (ret == 0 && info.frame > last) {
			last = info.frame;
			got++;
		}
		usleep(20000);
	}
	dk_shm_close(&r);
	return 0;
}

int waitChild(pid_t child)
{
	int status = 0;
	waitpid(child, &status, 0);
	return WIFEXITED(status) ? WEXITSTATUS(status) : 200 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
}

} // namespace

TEST(DaemonShmTamper, AReaderOfTheGroupCannotKillOrSilenceTheStream)
{
	if (geteuid() != 0)
		GTEST_SKIP() << "needs root to play a reader of another uid";
	struct group *video = getgrnam("video");
	if (!video)
		GTEST_SKIP() << "no video group";
	const gid_t group = video->gr_gid;
	DaemonProcess daemon;
	const std::string prefix = "/depthkey-tamper-" + std::to_string(getpid());
	const std::string composite = prefix + ".composite", lecturer = prefix + ".lecturer";
	const std::string config = daemon.writeFile(
		"depthkey.toml", "[colour]\nwidth = 160\nheight = 120\n[output]\ngroup = \"video\"\ncomposite_name = \"" +
					 composite + "\"\nlecturer_name = \"" + lecturer + "\"\n");
	ASSERT_TRUE(daemon.start({ "--config", config }));
	ASSERT_TRUE(daemon.waitForNotify("READY=1", 10s)) << daemon.log();
	ASSERT_TRUE(daemon.waitForNotify("output ", 3s)) << daemon.log();

	pid_t attacker = fork();
	ASSERT_GE(attacker, 0);
	if (attacker == 0) {
		if (!becomeAReaderOfTheGroup(group))
			_exit(100);
		_exit(tryToHarm(composite) | tryToHarm(lecturer));
	}
	EXPECT_EQ(waitChild(attacker), 0) << "1: opened read-write, 2: shrank through a read-only fd, "
					     "4: mapped writable, 8: truncated by path, 16: presence not writable, "
					     "100: setuid";

	// The owner (root here) still can write the header: what the issue's
	// reader did. The daemon rewrites it at its next frame and says so.
	const int fd = shm_open(composite.c_str(), O_RDWR, 0);
	ASSERT_GE(fd, 0);
	void *map = mmap(nullptr, sizeof(dk_shm_header), PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
	close(fd);
	ASSERT_NE(map, MAP_FAILED);
	static_cast<dk_shm_header *>(map)->generation = 0;
	static_cast<dk_shm_header *>(map)->slot_count = 9;
	munmap(map, sizeof(dk_shm_header));

	// Both streams keep coming, and a reader of the group takes them.
	for (const std::string &name : { composite, lecturer }) {
		pid_t reader = fork();
		ASSERT_GE(reader, 0);
		if (reader == 0)
			_exit(readAsTheGroup(name, group, 5));
		EXPECT_EQ(waitChild(reader), 0) << name << ": 101: never opened, 102: not counted, "
						   "103: no new frames, 104: refused after a repair";
	}
	EXPECT_TRUE(daemon.running()) << daemon.log();
	// The shrunk presence objects were restored, and the journal said so.
	EXPECT_NE(daemon.log().find(composite + DK_SHM_PRESENCE_SUFFIX + ": 0 bytes"), std::string::npos)
		<< daemon.log();
	EXPECT_NE(daemon.log().find("shared-memory output repaired: " + composite +
				    ": rewrote the header, field 'slot_count = 9 (expected 2)'"),
		  std::string::npos)
		<< daemon.log();

	ASSERT_EQ(daemon.signal(SIGTERM), 0);
	EXPECT_EQ(daemon.waitExit(5s), 0) << daemon.log();
	for (const std::string &name : { composite, lecturer }) {
		EXPECT_EQ(openStatus(name.c_str()), -ENOENT) << name;
		EXPECT_EQ(shm_unlink((name + DK_SHM_PRESENCE_SUFFIX).c_str()), -1) << "left behind: " << name;
		shm_unlink(name.c_str());
	}
}
