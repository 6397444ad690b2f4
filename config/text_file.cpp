// POSIX I/O rather than iostreams, so a failure keeps its errno.
#include "config/text_file.hpp"

#include <cerrno>
#include <fcntl.h>
#include <unistd.h>

namespace depthkey {

int readTextFile(const std::string &path, std::string &text, const char *&step)
{
	step = "open";
	int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
	if (fd < 0)
		return -errno;

	step = "read";
	text.clear();
	char buf[4096];
	for (;;) {
		ssize_t n = ::read(fd, buf, sizeof(buf));
		if (n < 0 && errno == EINTR)
			continue;
		if (n < 0) {
			int ret = -errno;
			::close(fd);
			return ret;
		}
		if (n == 0)
			break;
		text.append(buf, static_cast<size_t>(n));
	}
	::close(fd);
	return 0;
}

} // namespace depthkey
