// ShmRingWriter's checks: arguments, object mode and group, one writer per
// object. (The ring itself is tested in shm_ring_test.cpp.)
#include "hal/depthkey_shm.h"
#include "hal/shm_ring_writer.hpp"
#include "tests/shm_test_util.hpp"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/stat.h>

using namespace depthkey;
using depthkey::test::openStatus;
using depthkey::test::ShmName;

namespace {

struct stat statObject(const std::string &name)
{
	struct stat st{};
	int fd = shm_open(name.c_str(), O_RDONLY, 0);
	if (fd >= 0) {
		fstat(fd, &st);
		close(fd);
	}
	return st;
}

// An object as someone else might have left it: mode 0666.
int precreate(const std::string &name)
{
	int fd = shm_open(name.c_str(), O_RDWR | O_CREAT | O_EXCL, 0666);
	if (fd >= 0)
		fchmod(fd, 0666);
	return fd;
}

} // namespace

TEST(ShmRingWriter, BadArgumentsRejected)
{
	ShmName name;
	ShmRingWriter writer;
	uint8_t pixels[64] = {};
	EXPECT_EQ(writer.write(pixels, 24, 0, 0), -EBADF);
	EXPECT_NE(writer.describeError().find("closed"), std::string::npos);
	EXPECT_EQ(writer.open("no-slash", 8, 8, DK_SHM_FORMAT_RGB24, 2, ""), -EINVAL);
	EXPECT_EQ(writer.open(name.str(), 8, 8, DK_SHM_FORMAT_RGB24, 1, ""), -EINVAL);
	EXPECT_EQ(writer.open(name.str(), 8, 8, DK_SHM_FORMAT_RGB24, 9, ""), -EINVAL);
	EXPECT_EQ(writer.open(name.str(), 0, 8, DK_SHM_FORMAT_RGB24, 2, ""), -EINVAL);
	EXPECT_EQ(writer.open(name.str(), 8, 8, DK_SHM_FOURCC('Y', 'U', 'Y', 'V'), 2, ""), -EINVAL);
	EXPECT_NE(writer.describeError().find(name.str()), std::string::npos);
	EXPECT_EQ(openStatus(name.c_str()), -ENOENT); // nothing created

	ASSERT_EQ(writer.open(name.str(), 8, 8, DK_SHM_FORMAT_RGB24, 2, ""), 0);
	EXPECT_EQ(writer.write(pixels, 23, 0, 0), -EINVAL);
	EXPECT_EQ(writer.write(nullptr, 24, 0, 0), -EINVAL);
}

TEST(ShmRingWriter, UnknownGroupNamed)
{
	ShmName name;
	ShmRingWriter writer;
	EXPECT_EQ(writer.open(name.str(), 8, 8, DK_SHM_FORMAT_RGB24, 2, "depthkey-no-such-group"),
		  -ENOENT);
	const std::string message = writer.describeError();
	EXPECT_NE(message.find("depthkey-no-such-group"), std::string::npos) << message;
	EXPECT_NE(message.find(name.str()), std::string::npos) << message;
	EXPECT_EQ(openStatus(name.c_str()), -ENOENT); // checked before creating
}

TEST(ShmRingWriter, ModeAndGroup)
{
	ShmName name;
	ShmRingWriter writer;
	const mode_t oldMask = umask(077); // must not narrow the group's read bit
	int ret = writer.open(name.str(), 8, 8, DK_SHM_FORMAT_RGB24, 2, std::to_string(getegid()));
	umask(oldMask);
	ASSERT_EQ(ret, 0) << writer.describeError();
	// Issue 31: the group reads the frames and writes only its heartbeats.
	const struct stat frames = statObject(name.str()), presence = statObject(name.presence());
	EXPECT_EQ(frames.st_mode & 0777, 0640u);
	EXPECT_EQ(frames.st_gid, getegid());
	EXPECT_EQ(presence.st_mode & 0777, 0660u);
	EXPECT_EQ(presence.st_gid, getegid());
}

TEST(ShmRingWriter, SecondWriterRefused)
{
	ShmName name;
	ShmRingWriter first, second;
	ASSERT_EQ(first.open(name.str(), 8, 8, DK_SHM_FORMAT_RGB24, 2, ""), 0);
	EXPECT_EQ(second.open(name.str(), 8, 8, DK_SHM_FORMAT_RGB24, 2, ""), -EBUSY);
	EXPECT_NE(second.describeError().find("another writer"), std::string::npos);
	first.close();
	EXPECT_EQ(second.open(name.str(), 8, 8, DK_SHM_FORMAT_RGB24, 2, ""), 0);
	EXPECT_EQ(second.unlink(), 0);
	EXPECT_EQ(openStatus(name.c_str()), -ENOENT);
}


// Issue 14: an existing object is never reused; ours is replaced by a fresh
// one (O_EXCL) with our mode, so whoever held an fd to the old one (or made
// it 0666) holds nothing that the frames go to.
TEST(ShmRingWriter, StaleObjectIsReplacedNotReused)
{
	ShmName name;
	int old = precreate(name.str());
	ASSERT_GE(old, 0);
	ShmRingWriter writer;
	ASSERT_EQ(writer.open(name.str(), 8, 8, DK_SHM_FORMAT_RGB24, 2, ""), 0) << writer.describeError();
	struct stat before{}, now = statObject(name.str());
	ASSERT_EQ(fstat(old, &before), 0);
	EXPECT_EQ(before.st_nlink, 0u); // the old object was unlinked
	EXPECT_NE(now.st_ino, before.st_ino);
	EXPECT_EQ(now.st_mode & 0777, 0640u);
	EXPECT_EQ(before.st_size, 0); // and never sized or written by the writer
	close(old);
}

// Case K: an object created beforehand by another user with mode 0666 was
// taken over (mode 0640, but that user stayed the owner). Needs root to
// play the other user.
TEST(ShmRingWriter, ObjectOfAnotherUserIsRefused)
{
	if (geteuid() != 0)
		GTEST_SKIP() << "needs root to create an object owned by another user";
	ShmName name;
	int fd = precreate(name.str());
	ASSERT_GE(fd, 0);
	ASSERT_EQ(fchown(fd, 65534, 65534), 0);
	ShmRingWriter writer;
	EXPECT_EQ(writer.open(name.str(), 8, 8, DK_SHM_FORMAT_RGB24, 2, ""), -EPERM);
	const std::string message = writer.describeError();
	EXPECT_NE(message.find(name.str() + ": refusing an object owned by 'uid 65534'"), std::string::npos)
		<< message;
	struct stat st{};
	ASSERT_EQ(fstat(fd, &st), 0);
	EXPECT_EQ(st.st_nlink, 1u); // left alone for its owner or an admin
	EXPECT_EQ(st.st_mode & 0777, 0666u);
	EXPECT_EQ(st.st_size, 0);
	close(fd);
}

// Case J: output.group set back to "" left the objects in the old group, also
// across restarts. Needs root to chgrp to a group we are not in.
TEST(ShmRingWriter, EmptyGroupIsOurOwnGroupAgain)
{
	if (geteuid() != 0)
		GTEST_SKIP() << "needs root to chgrp to another group";
	ShmName name;
	const gid_t other = getegid() == 4242 ? 4243 : 4242;
	ShmRingWriter writer;
	ASSERT_EQ(writer.open(name.str(), 8, 8, DK_SHM_FORMAT_RGB24, 2, std::to_string(other)), 0);
	EXPECT_EQ(statObject(name.str()).st_gid, other);
	ASSERT_EQ(writer.open(name.str(), 8, 8, DK_SHM_FORMAT_RGB24, 2, ""), 0);
	EXPECT_EQ(statObject(name.str()).st_gid, getegid());
	// A restart (a new writer on the name left behind) likewise.
	ASSERT_EQ(writer.open(name.str(), 8, 8, DK_SHM_FORMAT_RGB24, 2, std::to_string(other)), 0);
	writer.close();
	ShmRingWriter restarted;
	ASSERT_EQ(restarted.open(name.str(), 8, 8, DK_SHM_FORMAT_RGB24, 2, ""), 0);
	EXPECT_EQ(statObject(name.str()).st_gid, getegid());
	EXPECT_EQ(statObject(name.presence()).st_gid, getegid());
	EXPECT_EQ(statObject(name.str()).st_mode & 0777, 0640u);
}
