// The owned file descriptor (hal/unique_fd.hpp): closed at scope exit and on
// reset, handed over by a move or release() without closing, errno kept.
#include "hal/unique_fd.hpp"

#include <gtest/gtest.h>

#include <cerrno>
#include <fcntl.h>

using namespace depthkey;

namespace {

bool isOpen(int fd)
{
	return fcntl(fd, F_GETFD) >= 0;
}

} // namespace

TEST(UniqueFd, ClosesAtScopeExitAndOnReset)
{
	int raw;
	{
		UniqueFd fd(open("/dev/null", O_RDONLY | O_CLOEXEC));
		ASSERT_TRUE(fd.isValid());
		raw = fd.get();
		EXPECT_TRUE(isOpen(raw));
	}
	EXPECT_FALSE(isOpen(raw));

	UniqueFd fd(open("/dev/null", O_RDONLY | O_CLOEXEC));
	raw = fd.get();
	errno = ENOSPC; // the error being reported when the fd is dropped
	fd.reset();
	EXPECT_EQ(errno, ENOSPC);
	EXPECT_FALSE(isOpen(raw));
	EXPECT_FALSE(fd.isValid());
}

TEST(UniqueFd, MoveAndReleaseHandItOverWithoutClosing)
{
	UniqueFd a(open("/dev/null", O_RDONLY | O_CLOEXEC));
	const int raw = a.get();
	UniqueFd b(std::move(a));
	EXPECT_FALSE(a.isValid());
	EXPECT_EQ(b.get(), raw);
	EXPECT_TRUE(isOpen(raw));

	UniqueFd c;
	c = std::move(b);
	EXPECT_EQ(c.get(), raw);
	EXPECT_TRUE(isOpen(raw));

	// Assigning over a held fd closes the old one.
	UniqueFd other(open("/dev/null", O_RDONLY | O_CLOEXEC));
	const int otherRaw = other.get();
	c = std::move(other);
	EXPECT_FALSE(isOpen(raw));
	EXPECT_EQ(c.get(), otherRaw);

	const int released = c.release();
	EXPECT_FALSE(c.isValid());
	EXPECT_TRUE(isOpen(released));
	close(released);
}
