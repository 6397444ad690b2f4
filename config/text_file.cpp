// POSIX I/O rather than iostreams, so a failure keeps its errno.
#include "config/text_file.hpp"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace depthkey {

const char *fileKindName(unsigned int mode)
{
	switch (mode & S_IFMT) {
	case S_IFREG:
		return "a regular file";
	case S_IFDIR:
		return "a directory";
	case S_IFIFO:
		return "a FIFO";
	case S_IFCHR:
		return "a character device";
	case S_IFBLK:
		return "a block device";
	case S_IFSOCK:
		return "a socket";
	default:
		return "not a file";
	}
}

int readTextFile(const std::string &path, size_t maxBytes, std::string &text, std::string &why)
{
	text.clear();
	int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
	if (fd < 0) {
		int ret = -errno;
		why = std::strerror(errno);
		return ret;
	}
	struct stat st{};
	int ret = 0;
	if (fstat(fd, &st) < 0) {
		ret = -errno;
		why = std::string("fstat: ") + std::strerror(errno);
	} else if (!S_ISREG(st.st_mode)) {
		ret = S_ISDIR(st.st_mode) ? -EISDIR : -EINVAL;
		why = std::string("not a regular file (") + fileKindName(st.st_mode) + ")";
	} else if (static_cast<unsigned long long>(st.st_size) > maxBytes) {
		ret = -EFBIG;
		why = "too large: " + std::to_string(st.st_size) + " bytes, at most " +
		      std::to_string(maxBytes);
	}
	if (ret < 0) {
		::close(fd);
		return ret;
	}

	// The size may change under us: never read more than the cap.
	text.resize(static_cast<size_t>(st.st_size));
	size_t used = 0;
	for (;;) {
		if (used == text.size())
			text.resize(used + 4096 > maxBytes + 1 ? maxBytes + 1 : used + 4096);
		if (used == text.size())
			break;
		ssize_t n = ::read(fd, text.data() + used, text.size() - used);
		if (n < 0 && errno == EINTR)
			continue;
		if (n < 0) {
			ret = -errno;
			why = std::string("read: ") + std::strerror(errno);
			break;
		}
		if (n == 0)
			break;
		used += static_cast<size_t>(n);
	}
	::close(fd);
	if (ret == 0 && used > maxBytes) {
		ret = -EFBIG;
		why = "too large: grew past " + std::to_string(maxBytes) + " bytes while read";
	}
	text.resize(ret < 0 ? 0 : used);
	return ret;
}

} // namespace depthkey
