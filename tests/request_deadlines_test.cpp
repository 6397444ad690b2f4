// Cutting connections whose request head is late
// (hal/preview/request_deadlines.hpp): a socket pair stands for a client's
// connection; the times are given.
#include "hal/preview/request_deadlines.hpp"

#include <gtest/gtest.h>

#include <sys/socket.h>
#include <unistd.h>

using namespace depthkey;

namespace {

constexpr uint64_t kSecond = 1000000000ull;

// True when the client's end reads the end of the stream (the server's
// end was shut down), without waiting.
bool clientSeesEnd(int fd)
{
	char c;
	return recv(fd, &c, 1, MSG_DONTWAIT) == 0;
}

} // namespace

TEST(RequestDeadlines, ALateHeadIsCutAndOneThatCameIsNot)
{
	int late[2], prompt[2], gone[2];
	ASSERT_EQ(socketpair(AF_UNIX, SOCK_STREAM, 0, late), 0);
	ASSERT_EQ(socketpair(AF_UNIX, SOCK_STREAM, 0, prompt), 0);
	ASSERT_EQ(socketpair(AF_UNIX, SOCK_STREAM, 0, gone), 0);
	RequestDeadlines deadlines(5 * kSecond);
	int a, b, c; // stand-ins for libmicrohttpd's connections
	deadlines.opened(&a, late[0], 0);
	deadlines.opened(&b, prompt[0], 0);
	deadlines.opened(&c, gone[0], 0);
	deadlines.arrived(&b);
	deadlines.closed(&c);
	EXPECT_EQ(deadlines.expire(4 * kSecond), 0);
	EXPECT_FALSE(clientSeesEnd(late[1]));
	EXPECT_EQ(deadlines.expire(5 * kSecond), 1);
	EXPECT_TRUE(clientSeesEnd(late[1]));
	EXPECT_FALSE(clientSeesEnd(prompt[1]));
	EXPECT_FALSE(clientSeesEnd(gone[1]));
	EXPECT_EQ(deadlines.expired(), 1u);
	EXPECT_EQ(deadlines.waiting(), 0u);
	EXPECT_EQ(deadlines.expire(60 * kSecond), 0) << "each once";
	for (int fd : { late[0], late[1], prompt[0], prompt[1], gone[0], gone[1] })
		close(fd);
}
