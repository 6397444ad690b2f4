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
	int fd = shm_open(name.c_str(), O_RDONLY, 0);
	struct stat st{};
	ASSERT_EQ(fstat(fd, &st), 0);
	close(fd);
	EXPECT_EQ(st.st_mode & 0777, 0660u);
	EXPECT_EQ(st.st_gid, getegid());
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
